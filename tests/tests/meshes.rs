//! Triangle meshes: OBJ files next to the scene, and a mesh prism that bends
//! light exactly like the analytic prism.

use prismatic_conformance::compare::image_correlation;
use prismatic_core::geometry::primitive::Primitive;
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::dispersion::Glass;
use prismatic_core::model::scene::Shape;
use prismatic_core::photons::trace::trace_photons;
use prismatic_core::{Scene, Vec3};
use prismatic_tests::{PrismExperiment, prepare, settings};

/// The prism's two caps and three sides as 8 triangles, wound counter-clockwise seen from outside.
fn prism_mesh(v: [Vec3; 3], extrude: Vec3) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let positions = vec![v[0], v[1], v[2], v[0] + extrude, v[1] + extrude, v[2] + extrude];
    // With v0, v1, v2 counter-clockwise seen from −extrude: front cap reversed, back cap as is.
    let triangles = vec![[0, 2, 1], [3, 4, 5], [0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4], [2, 0, 3], [2, 3, 5]];
    (positions, triangles)
}

fn experiment() -> PrismExperiment {
    PrismExperiment { apex_deg: 60.0, incidence_deg: 50.0, beam_radius: 0.05, screen_x: 6.0 }
}

fn as_mesh(mut scene: Scene) -> Scene {
    let Shape::Prism { vertices, extrude } = scene.objects[0].shape else { unreachable!("object 0 is the prism") };
    let (positions, triangles) = prism_mesh(vertices, extrude);
    scene.objects[0].shape =
        Shape::Mesh { positions, triangles, uvs: Vec::new(), normals: Vec::new(), tangents: Vec::new() };
    scene
}

#[test]
fn a_mesh_prism_disperses_like_the_analytic_prism() {
    let analytic = experiment().scene(Glass::Bk7.dispersion(), settings(2000, BandSpec::Paper7));
    let a = trace_photons(&prepare(analytic.clone()), &mut prismatic_core::NoProgress);
    let m = trace_photons(&prepare(as_mesh(analytic)), &mut prismatic_core::NoProgress);
    // The same photons take the same branches; positions agree to f32 precision.
    let twice = |map: &prismatic_core::PhotonMap| map.photons.iter().filter(|p| p.bounces == 2).count();
    assert!(twice(&a) > 12_000, "most of 2000 × 7 band photons refract twice");
    let keys = |map: &prismatic_core::PhotonMap| map.photons.iter().map(|p| p.key()).collect::<Vec<_>>();
    assert_eq!(keys(&a), keys(&m), "the same (emission, band) photons are stored");
    for (pa, pm) in a.photons.iter().zip(&m.photons) {
        assert!((pa.pos() - pm.pos()).length() < 1e-3, "{:?} vs {:?}", pa.position, pm.position);
    }
}

#[test]
fn obj_meshes_load_relative_to_the_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    let exp = experiment();
    let [l, r, t] = exp.corners().map(|(x, y)| Vec3::new(x as f32, y as f32, -1.0));
    let (positions, triangles) = prism_mesh([l, r, t], Vec3::new(0.0, 0.0, 2.0));
    let mut obj = String::from("# prism\n");
    for p in &positions {
        obj += &format!("v {} {} {}\n", p.x, p.y, p.z);
    }
    obj += "vt 0 0\nvn 0 0 1\nvn 0 1 0\n";
    for tri in &triangles {
        obj += &format!("f {} {}/1 {}//2\n", tri[0] + 1, tri[1] + 1, tri[2] + 1);
    }
    std::fs::create_dir(dir.path().join("models")).unwrap();
    std::fs::write(dir.path().join("models/prism.obj"), obj).unwrap();
    let scene = format!(
        "[render]\nphotons = 500\n\n[camera]\nposition = [0, 0, 10]\nlook_at = [0, 0, 0]\n\n\
         [[light]]\nkind = \"beam\"\nposition = [-3.6, -1.1, 0]\ndirection = [{}, {}, 0]\nradius = 0.05\npower = 1\n\n\
         [material.glass]\nkind = \"dielectric\"\nior = \"bk7\"\n\n[material.screen]\nkind = \"diffuse\"\n\n\
         [[object]]\nshape = \"mesh\"\nmaterial = \"glass\"\npath = \"models/prism.obj\"\n\n\
         [[object]]\nshape = \"plane\"\nmaterial = \"screen\"\npoint = [6, 0, 0]\nnormal = [-1, 0, 0]\n",
        exp.beam_angle().cos(),
        exp.beam_angle().sin()
    );
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, scene).unwrap();
    let doc = prismatic_cli::scene_file::load(&path).unwrap_or_else(|e| panic!("{e}"));
    doc.validate().unwrap();
    assert!(matches!(&doc.scene.objects[0].shape, Shape::Mesh { triangles, .. } if triangles.len() == 8));

    // A broken OBJ names the OBJ file and its line, under the scene's key.
    std::fs::write(dir.path().join("models/prism.obj"), "v 0 0 0\nf 1 2 3\n").unwrap();
    let e = prismatic_cli::scene_file::load(&path).unwrap_err();
    assert_eq!(e.key, "object[0].path");
    assert!(e.reason.contains("prism.obj:2") && e.reason.contains("does not exist"), "{e}");
}

/// The paper's sphere as a closed mesh of about 100,000 triangles renders
/// the analytic sphere's image (caustic, refracted floor, rim) on every
/// backend: the hierarchy finds the hits the sphere has, to the facets.
#[test]
fn a_fine_mesh_sphere_renders_the_analytic_spheres_image_on_every_backend() {
    let analytic = prismatic_tests::builtin("sphere", |r| {
        (r.width, r.height, r.photons) = (120, 120, 20_000);
    });
    let mut scene = analytic.scene.clone();
    let Shape::Sphere { center, radius } = scene.objects[1].shape else { unreachable!("object 1 is the sphere") };
    scene.objects[1].shape = prismatic_conformance::scenes::sphere_mesh(center, radius, 158);
    let mesh = prepare(scene);
    let Primitive::Mesh(bvh) = &mesh.primitives[1] else { unreachable!() };
    assert!(bvh.triangles.len() > 99_000, "{} triangles", bvh.triangles.len());
    for mut backend in prismatic_tests::backends::every_backend() {
        let (_, want) = prismatic_tests::backends::frame(backend.as_mut(), &analytic);
        let (_, got) = prismatic_tests::backends::frame(backend.as_mut(), &mesh);
        let r = image_correlation(&want, &got);
        assert!(r >= 0.95, "{}: correlation {r:.4}", backend.name());
    }
}

#[test]
fn an_updated_scene_keeps_its_hierarchies_and_traces_as_a_fresh_one() {
    use prismatic_core::{Backend, NoProgress, PreparedScene};
    let before = prismatic_conformance::scenes::glass_mesh_sphere(20);
    let Primitive::Mesh(built) = &before.primitives[1] else { unreachable!("object 1 is the mesh") };
    // The camera moves: the mesh's hierarchy is copied.
    let mut scene = before.scene.clone();
    scene.camera.position += Vec3::new(0.3, 0.1, 0.0);
    let camera_moved = before.update(scene.clone()).unwrap();
    assert_eq!(camera_moved.primitives[1], before.primitives[1]);
    // The mesh moves and stretches: the same tree, refitted.
    let Shape::Mesh { positions, .. } = &mut scene.objects[1].shape else { unreachable!() };
    for p in positions.iter_mut() {
        *p = Vec3::new(p.x * 1.3, p.y * 0.9 + 0.05, p.z) + Vec3::new(0.2, 0.0, -0.1);
    }
    let updated = before.update(scene.clone()).unwrap();
    let Primitive::Mesh(refitted) = &updated.primitives[1] else { unreachable!() };
    assert_eq!((refitted.nodes.len(), &refitted.sources), (built.nodes.len(), &built.sources));
    assert_ne!(refitted.nodes[0], built.nodes[0], "the root's box grew with the mesh");
    // Traced, the refitted scene is the freshly built one, on the reference and the CPU backend.
    let fresh = PreparedScene::new(scene).unwrap();
    assert_ne!(updated.primitives[1], fresh.primitives[1], "a rebuilt tree has another shape");
    let reference = trace_photons(&fresh, &mut NoProgress);
    assert!(reference.photons.len() > 1000, "{} photons", reference.photons.len());
    assert_eq!(trace_photons(&updated, &mut NoProgress), reference);
    let mut cpu = prismatic_cpu::CpuBackend::new();
    let map = cpu.prepare(&updated).unwrap().photon_map(0, &mut NoProgress).unwrap();
    assert_eq!(map, cpu.prepare(&fresh).unwrap().photon_map(0, &mut NoProgress).unwrap());
}

#[test]
fn an_update_still_refuses_glass_that_is_not_closed() {
    let before = prismatic_conformance::scenes::glass_mesh_sphere(6);
    // The glass mesh loses a triangle.
    let mut open = before.scene.clone();
    let Shape::Mesh { triangles, .. } = &mut open.objects[1].shape else { unreachable!() };
    triangles.remove(triangles.len() / 2);
    let refusal = |r: Result<prismatic_core::PreparedScene, _>| r.err().map(|e: prismatic_core::SceneError| e.reason);
    assert!(refusal(before.update(open.clone())).is_some_and(|r| r.contains("needs a closed mesh")));
    // An open diffuse mesh (never checked) that becomes glass.
    open.materials[1].kind = open.materials[0].kind.clone();
    let diffuse = prismatic_core::PreparedScene::new(open.clone()).expect("an open diffuse mesh is fine");
    open.materials[1].kind = before.scene.materials[1].kind.clone();
    assert!(refusal(diffuse.update(open)).is_some_and(|r| r.contains("needs a closed mesh")));
}
