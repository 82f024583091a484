//! Base-colour textures on every backend: a textured floor seen from above
//! and lit by an overhead sun shows each texel's colour where the closed
//! form puts it (the texture coordinates of the floor point a pixel sees,
//! found by intersecting its camera ray with the floor, not by the
//! renderer), for each filter and wrap mode; and a texture asked of a shape
//! without texture coordinates is refused with the material named.

use core::f32::consts::PI;
use prismatic_core::geometry::camera::PinholeCamera;
use prismatic_core::geometry::texture::sample;
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::scene::{
    Camera, Filter, Light, Material, MaterialKind, Object, Sampler, Shape, Texture, Wrap,
};
use prismatic_core::{PreparedScene, Scene, Vec3};
use prismatic_tests::backends::every_backend;
use prismatic_tests::settings;
use std::sync::Arc;

const IRRADIANCE: f32 = 2.0;
const SIDE: u32 = 48;
/// The floor spans −HALF..HALF in x and z.
const HALF: f32 = 2.0;

/// sRGB texels packed as the core keeps them.
fn rgb(r: u8, g: u8, b: u8) -> u32 {
    u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16
}

fn texture(width: u32, height: u32, texels: Vec<u32>, filter: Filter, wrap_u: Wrap, wrap_v: Wrap) -> Texture {
    Texture {
        name: "test.png".into(),
        width,
        height,
        texels: Arc::from(texels),
        sampler: Sampler { filter, wrap_u, wrap_v },
    }
}

/// The floor's texture coordinates at (x, 0, z): corner (−H, −H) reads
/// `lo`, corner (H, H) reads `hi`, linearly between.
fn uv_at(x: f32, z: f32, lo: f32, hi: f32) -> [f32; 2] {
    let t = |c: f32| lo + (hi - lo) * (c + HALF) / (2.0 * HALF);
    [t(x), t(z)]
}

/// A textured floor quad (two triangles) at y = 0 under an overhead sun,
/// seen from straight above so that it fills the image.
fn scene(texture: Texture, albedo: Vec3, lo: f32, hi: f32) -> PreparedScene {
    let mut render = settings(1000, BandSpec::Paper3);
    (render.width, render.height, render.ambient) = (SIDE, SIDE, 0.0);
    let corners = [(-HALF, -HALF), (HALF, -HALF), (HALF, HALF), (-HALF, HALF)];
    let floor = Shape::Mesh {
        positions: corners.iter().map(|&(x, z)| Vec3::new(x, 0.0, z)).collect(),
        triangles: vec![[0, 2, 1], [0, 3, 2]],
        uvs: corners.iter().map(|&(x, z)| uv_at(x, z, lo, hi).into()).collect(),
        normals: Vec::new(),
        tangents: Vec::new(),
    };
    let material = MaterialKind::Diffuse { albedo, checker: None, texture: Some(texture), emission: Vec3::ZERO };
    PreparedScene::new(Scene {
        render,
        // Seen from 10 above with a 20° field: the view is ±1.76 wide, inside the floor.
        camera: Camera { position: Vec3::new(0.0, 10.0, 0.0), look_at: Vec3::ZERO, up: Vec3::Z, fov_deg: 20.0 },
        lights: vec![Light::Sun {
            direction: Vec3::NEG_Y,
            irradiance: IRRADIANCE,
            spectrum: Default::default(),
            mean_toward: None,
        }],
        materials: vec![Material::new("floor", material)],
        objects: vec![Object { shape: floor, material: 0 }],
    })
    .expect("a valid scene")
}

/// What each pixel must show: albedo × texture at the coordinates of the
/// floor point its ray meets, times E/π.
fn closed_form(scene: &PreparedScene, lo: f32, hi: f32) -> Vec<Vec3> {
    let Some(Material { kind: MaterialKind::Diffuse { albedo, texture: Some(texture), .. }, .. }) =
        scene.scene.materials.first()
    else {
        unreachable!("the scene's one material is textured")
    };
    let camera = PinholeCamera::new(&scene.scene.camera, SIDE, SIDE);
    (0..SIDE * SIDE)
        .map(|i| {
            let ray = camera.ray(i % SIDE, i / SIDE);
            let p = ray.origin + ray.direction * (-ray.origin.y / ray.direction.y);
            *albedo * sample(texture, uv_at(p.x, p.z, lo, hi).into()) * (IRRADIANCE / PI)
        })
        .collect()
}

/// Renders the view pass of `scene` on every backend and compares each
/// pixel with the closed form within 2e-5.
fn assert_matches_closed_form(case: &str, scene: &PreparedScene, lo: f32, hi: f32) {
    let expected = closed_form(scene, lo, hi);
    for mut backend in every_backend() {
        let name = backend.name();
        let base = backend.prepare(scene).unwrap().base().unwrap();
        let off: Vec<(usize, Vec3, Vec3)> = base
            .pixels
            .iter()
            .zip(&expected)
            .enumerate()
            .filter(|(_, (got, want))| (**got - **want).abs().max_element() > 2e-5)
            .map(|(i, (got, want))| (i, *got, *want))
            .collect();
        assert!(off.is_empty(), "{case}, {name}: {} pixels off the closed form, first {:?}", off.len(), off.first());
    }
}

#[test]
fn each_texel_shows_where_its_coordinates_put_it() {
    // 2×2 texels, nearest: red, green on the top row (v = 0), blue and a
    // mid grey (sRGB 188: 0.503 in linear light) below.
    let texels = vec![rgb(255, 0, 0), rgb(0, 255, 0), rgb(0, 0, 255), rgb(188, 188, 188)];
    let t = texture(2, 2, texels, Filter::Nearest, Wrap::ClampToEdge, Wrap::ClampToEdge);
    let scene = scene(t, Vec3::splat(0.9), 0.0, 1.0);
    // The pixel that sees (x, z): the camera looks down −y, +z up the image, +x to the left.
    let quadrant = |image: &[Vec3], x: f32, z: f32| {
        let half = 10.0 * 10f32.to_radians().tan();
        let col = ((-x / half + 1.0) * SIDE as f32 / 2.0) as usize;
        let row = ((-z / half + 1.0) * SIDE as f32 / 2.0) as usize;
        image[row * SIDE as usize + col]
    };
    let lit = 0.9 * IRRADIANCE / PI;
    let grey = prismatic_core::geometry::texture::srgb_to_linear(188);
    for mut backend in every_backend() {
        let name = backend.name();
        let base = backend.prepare(&scene).unwrap().base().unwrap();
        for ((x, z), colour) in
            [((-1.0, -1.0), Vec3::X), ((1.0, -1.0), Vec3::Y), ((-1.0, 1.0), Vec3::Z), ((1.0, 1.0), Vec3::splat(grey))]
        {
            let got = quadrant(&base.pixels, x, z);
            assert!(
                (got - colour * lit).abs().max_element() < 1e-5,
                "{name}: at ({x}, {z}) {got}, expected {}",
                colour * lit
            );
        }
    }
    assert_matches_closed_form("nearest, clamped", &scene, 0.0, 1.0);
}

#[test]
fn bilinear_filtering_and_every_wrap_mode_match_the_closed_form() {
    // A 4×3 image of distinct colours, read over coordinates from −1.3 to
    // 2.2: every wrap mode reaches beyond the image on both sides.
    let texels: Vec<u32> =
        (0..12u32).map(|i| rgb((i * 21) as u8, (255 - i * 19) as u8, ((i * 97) % 256) as u8)).collect();
    for (wrap_u, wrap_v) in
        [(Wrap::Repeat, Wrap::Repeat), (Wrap::ClampToEdge, Wrap::MirroredRepeat), (Wrap::MirroredRepeat, Wrap::Repeat)]
    {
        for filter in [Filter::Linear, Filter::Nearest] {
            let t = texture(4, 3, texels.clone(), filter, wrap_u, wrap_v);
            let scene = scene(t, Vec3::new(1.0, 0.8, 0.6), -1.3, 2.2);
            assert_matches_closed_form(&format!("{filter:?}, {wrap_u:?} × {wrap_v:?}"), &scene, -1.3, 2.2);
        }
    }
}

#[test]
fn a_texture_needs_a_mesh_with_texture_coordinates() {
    let t = texture(1, 1, vec![rgb(9, 9, 9)], Filter::Linear, Wrap::Repeat, Wrap::Repeat);
    let mut scene = scene(t, Vec3::ONE, 0.0, 1.0).scene;
    scene.objects[0].shape = Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y };
    let err = PreparedScene::new(scene.clone()).unwrap_err();
    assert_eq!(err.key, "object[0].material");
    assert!(err.reason.contains("'floor' has the texture test.png") && err.reason.contains("plane"), "{err}");
    scene.objects[0].shape = Shape::Mesh {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::Z],
        triangles: vec![[0, 1, 2]],
        uvs: Vec::new(),
        normals: Vec::new(),
        tangents: Vec::new(),
    };
    assert!(PreparedScene::new(scene.clone()).unwrap_err().reason.contains("mesh has none"));
    scene.objects[0].shape = Shape::Mesh {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::Z],
        triangles: vec![[0, 1, 2]],
        uvs: vec![[0.0, 0.0].into(); 2],
        normals: Vec::new(),
        tangents: Vec::new(),
    };
    assert_eq!(PreparedScene::new(scene).unwrap_err().key, "object[0].uvs");
}
