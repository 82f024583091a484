//! Normal maps on every backend: a flat mirror whose map tilts every
//! normal by one angle turns a beam by twice that angle, toward the
//! tangent or up the image as glTF's tangent space has it, whether the
//! frame comes from the texture coordinates or from the mesh's tangents.

use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::scene::{Light, Material, MaterialKind, NormalMap, Object, Sampler, Shape, Texture};
use prismatic_core::{Scene, Vec3, Vec4};
use prismatic_tests::backends::{every_backend, trace};
use prismatic_tests::{camera, prepare, settings, white};

const PHOTONS: u32 = 2000;

/// One texel encoding the unit tangent-space normal `n` (8-bit linear channels).
fn texel(n: Vec3) -> Texture {
    let byte = |x: f32| ((x + 1.0) * 0.5 * 255.0).round() as u32;
    Texture {
        name: "tilt".into(),
        width: 1,
        height: 1,
        texels: vec![byte(n.x) | byte(n.y) << 8 | byte(n.z) << 16].into(),
        sampler: Sampler::default(),
    }
}

/// A 2×2 mirror in the plane y = 0 facing up, its image laid with u along
/// `u_axis` and v along +z, mapped by `map`, with `tangents` per corner
/// (empty: from the texture coordinates); a beam straight down onto it
/// inside a white catcher of radius 50.
fn mapped_mirror(map: NormalMap, u_axis: f32, tangents: Vec<Vec4>) -> Scene {
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let mirror = Shape::Mesh {
        positions: corners.iter().map(|&(x, z)| Vec3::new(x, 0.0, z)).collect(),
        triangles: vec![[0, 3, 2], [0, 2, 1]],
        uvs: corners.iter().map(|&(x, z)| [(u_axis * x + 1.0) * 0.5, (z + 1.0) * 0.5].into()).collect(),
        normals: Vec::new(),
        tangents,
    };
    Scene {
        render: settings(PHOTONS, BandSpec::Paper3),
        camera: camera(),
        lights: vec![Light::Beam {
            position: Vec3::new(0.0, 5.0, 0.0),
            direction: -Vec3::Y,
            radius: 0.3,
            power: 1.0,
            spectrum: Default::default(),
        }],
        materials: vec![
            white("catcher"),
            Material { normal_map: Some(map), ..Material::new("mirror", MaterialKind::Mirror) },
        ],
        objects: vec![
            Object { shape: Shape::Sphere { center: Vec3::ZERO, radius: 50.0 }, material: 0 },
            Object { shape: mirror, material: 1 },
        ],
    }
}

/// The largest angle (degrees) between the photons' directions and `want`.
fn widest_angle(scene: Scene, want: Vec3) -> Vec<(String, f32)> {
    let scene = prepare(scene);
    every_backend()
        .into_iter()
        .map(|mut backend| {
            let map = trace(backend.as_mut(), &scene);
            let stored = map.photons.len();
            assert!(stored > PHOTONS as usize / 2, "{}: {stored} photons reach the catcher", backend.name());
            let angle = map.photons.iter().map(|p| p.direction().angle_between(want).to_degrees()).fold(0.0, f32::max);
            (backend.name().to_string(), angle)
        })
        .collect()
}

/// The beam (straight down) mirrored about the normal that `texture`'s
/// texel encodes, X and Y scaled by `scale`, in the frame (tangent,
/// bitangent, +y): the closed form the renders are held to.
fn mirrored(texture: &Texture, scale: f32, tangent: Vec3, bitangent: Vec3) -> Vec3 {
    let t = texture.texels[0];
    let channel = |shift: u32| ((t >> shift) & 255) as f32 / 255.0 * 2.0 - 1.0;
    let n = (tangent * channel(0) * scale + bitangent * channel(8) * scale + Vec3::Y * channel(16)).normalize();
    let d = -Vec3::Y;
    d - n * (2.0 * d.dot(n))
}

#[test]
fn a_normal_maps_tilt_turns_a_mirrors_beam_by_twice_the_tilt_on_every_backend() {
    let tilt = 10f32.to_radians();
    let (toward_x, toward_y) = (Vec3::new(tilt.sin(), 0.0, tilt.cos()), Vec3::new(0.0, tilt.sin(), tilt.cos()));
    // (what the case shows, the map, u along ±x, the mesh's tangents, the frame's tangent and bitangent)
    let cases = [
        ("toward the tangent, u along +x", texel(toward_x), 1.0, 1.0, Vec::new(), Vec3::X, -Vec3::Z),
        ("up the image, v along +z", texel(toward_y), 1.0, 1.0, Vec::new(), Vec3::X, -Vec3::Z),
        ("scaled by a half", texel(toward_x), 0.5, 1.0, Vec::new(), Vec3::X, -Vec3::Z),
        ("a mirrored image, u along −x", texel(toward_x), 1.0, -1.0, Vec::new(), -Vec3::X, -Vec3::Z),
        (
            "the mesh's tangents along +z, w = −1",
            texel(toward_x),
            1.0,
            1.0,
            vec![Vec3::Z.extend(-1.0); 4],
            Vec3::Z,
            -Vec3::X,
        ),
    ];
    for (case, texture, scale, u_axis, tangents, tangent, bitangent) in cases {
        let want = mirrored(&texture, scale, tangent, bitangent);
        // Twice the tilt off the vertical (a half scale: less than that).
        let off = want.angle_between(Vec3::Y).to_degrees();
        assert!(if scale == 1.0 { (off - 20.0).abs() < 0.5 } else { off < 15.0 }, "{case}: {off}°");
        for (backend, angle) in widest_angle(mapped_mirror(NormalMap { texture, scale }, u_axis, tangents), want) {
            assert!(angle < 0.05, "{case}: {backend}: photons up to {angle:.3}° off {want}");
        }
    }
}

/// A map of scale 0 leaves the mirror a mirror: the beam comes straight
/// back up. The plain texel (128, 128, 255) tilts the normal by its 8-bit
/// rounding alone (128/255 is not ½): 0.32°, the beam twice that.
#[test]
fn scale_zero_leaves_the_mirror_plain_and_the_plain_texel_tilts_by_its_rounding() {
    let tilted = NormalMap { texture: texel(Vec3::new(0.5, 0.3, 0.81).normalize()), scale: 0.0 };
    for (backend, angle) in widest_angle(mapped_mirror(tilted, 1.0, Vec::new()), Vec3::Y) {
        assert!(angle < 0.05, "{backend}: photons up to {angle:.3}° off straight up");
    }
    let plain = texel(Vec3::Z);
    let want = mirrored(&plain, 1.0, Vec3::X, -Vec3::Z);
    assert!((want.angle_between(Vec3::Y).to_degrees() - 0.635).abs() < 0.01);
    let map = NormalMap { texture: plain, scale: 1.0 };
    for (backend, angle) in widest_angle(mapped_mirror(map, 1.0, Vec::new()), want) {
        assert!(angle < 0.05, "{backend}: photons up to {angle:.3}° off {want}");
    }
}

/// A scene file gives any material a `normal_map` (a PNG beside it, read
/// as linear bytes) and `normal_scale`, and a mesh its `tangents`; what
/// makes no sense is refused with its key.
#[test]
fn scene_files_give_materials_normal_maps_and_meshes_tangents() {
    let dir = tempfile::tempdir().unwrap();
    image::RgbImage::from_raw(1, 1, vec![160, 120, 240]).unwrap().save(dir.path().join("bumps.png")).unwrap();
    let scene = |material: &str, shape: &str| {
        format!(
            "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 0, 0]\n\n\
             [[light]]\nkind = \"point\"\nposition = [0, 4, 0]\npower = 10\n\n\
             [material.gold]\nkind = \"metal\"\ncolor = \"gold\"\n{material}\n\n\
             [[object]]\nmaterial = \"gold\"\n{shape}\n"
        )
    };
    let quad = "shape = \"mesh\"\npositions = [[0, 0, 0], [1, 0, 0], [0, 0, -1]]\ntriangles = [[0, 1, 2]]\n\
                uvs = [[0, 1], [1, 1], [0, 0]]";
    let check = |material: &str, shape: &str| {
        let doc = prismatic_cli::scene_file::parse(&scene(material, shape), "test.toml", Some(dir.path()))?;
        doc.validate().map(|_| doc)
    };
    let map = "normal_map = \"bumps.png\"\nnormal_scale = 0.5";
    let given = "tangents = [[1, 0, 0, 1], [1, 0, 0, 1], [1, 0, 0, -1]]";
    let doc = check(map, &format!("{quad}\n{given}")).unwrap_or_else(|e| panic!("{e}"));
    let gold = &doc.scene.materials[0];
    let normal_map = gold.normal_map.as_ref().expect("gold's normal map");
    assert_eq!((normal_map.scale, normal_map.texture.texels[0]), (0.5, 160 | 120 << 8 | 240 << 16));
    let Shape::Mesh { tangents, .. } = &doc.scene.objects[0].shape else { panic!("a mesh") };
    assert_eq!(tangents[2], Vec4::new(1.0, 0.0, 0.0, -1.0));
    for (material, shape, key, reason) in [
        ("normal_scale = 2", quad, "material.gold.normal_scale", "the material names none"),
        ("normal_map = \"missing.png\"", quad, "material.gold.normal_map", "cannot read texture"),
        (map, "shape = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1", "object[0].material", "normal map"),
        (map, &format!("{quad}\ntangents = [[1, 0, 0, 1]]"), "object[0].tangents", "1 tangents for 3 positions"),
        (map, &format!("{quad}\ntangents = [[1, 0, 0]]"), "object[0].tangents[0]", "must be [x, y, z, w]"),
        (map, &format!("{quad}\n{}", given.replace("-1]", "0]")), "object[0].tangents[2]", "handedness"),
    ] {
        let e = check(material, shape).map(|_| ()).unwrap_err();
        assert!(e.key == key && e.reason.contains(reason), "{material} / {shape}: {e}");
    }
}
