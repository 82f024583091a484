//! The scenes the suite renders, built in code (small: the scalar reference
//! renders each in well under a second): a dispersive glass sphere on a
//! checkered floor under a spot light (caustic, band split, visible points
//! seen through glass; once more as a closed triangle mesh, once more in
//! amber glass that absorbs, once more on a textured floor), a prism
//! fanning a beam onto a wall (split bands),
//! a mirror folding a beam onto a floor (no dispersion; once more rippled
//! by a normal map), the sphere under a
//! light panel (an area light), once more with indirect light, once more
//! under a sky (an environment light, whose suns per-pass view paths draw
//! anew each pass), and a room with no mirror or glass (no caustics at all).

use glam::Vec3;
use prismatic_core::model::dispersion::{Dispersion, Glass};
use prismatic_core::model::environment::EnvironmentMap;
use prismatic_core::model::metalness::{Metalness, SpecularLayer};
use prismatic_core::model::scene::{
    Attenuation, Camera, Checker, FilmMap, Filter, Light, Material, MaterialKind, NormalMap, Object, PhotonSequence,
    RenderSettings, Sampler, Shape, SpecularMap, Texture, ThinFilm, Wrap,
};
use prismatic_core::{BandSpec, Estimator, MetalColor, NamedMetal, PreparedScene, Scene};

/// A small render: `side`² pixels, `photons` photons a pass, paper7, `density`.
fn settings(side: u32, photons: u32, radius: f32) -> RenderSettings {
    RenderSettings {
        width: side,
        height: side,
        photons,
        radius,
        bands: BandSpec::Paper7,
        estimator: Estimator::Density,
        ..RenderSettings::paper()
    }
}

fn material(name: &str, kind: MaterialKind) -> Material {
    Material::new(name, kind)
}

fn diffuse(name: &str, albedo: f32) -> Material {
    material(
        name,
        MaterialKind::Diffuse { albedo: Vec3::splat(albedo), checker: None, texture: None, emission: Vec3::ZERO },
    )
}

fn glass(name: &str, dispersion: Dispersion) -> Material {
    material(
        name,
        MaterialKind::Dielectric {
            dispersion,
            outside: Dispersion::Constant(1.0),
            attenuation: None,
            thin: false,
            film: None,
            roughness: 0.0,
        },
    )
}

fn prepared(scene: Scene) -> PreparedScene {
    PreparedScene::new(scene).unwrap_or_else(|e| panic!("a conformance scene is invalid: {e}"))
}

/// The paper's sphere: dispersive glass on a checkered floor under a spot light.
pub fn glass_sphere() -> PreparedScene {
    let checker = Checker { size: 0.5, albedo: Vec3::splat(0.35), offset: Vec3::ZERO };
    prepared(Scene {
        render: settings(32, 6_000, 0.08),
        camera: Camera {
            position: Vec3::new(3.0, 2.4, 3.2),
            look_at: Vec3::new(0.3, 0.4, 0.0),
            up: Vec3::Y,
            fov_deg: 40.0,
        },
        lights: vec![Light::Spot {
            position: Vec3::new(-1.5, 6.0, -0.5),
            direction: Vec3::new(1.5, -6.0, 0.5),
            cone_deg: 30.0,
            inner_cone_deg: 30.0,
            power: 40.0,
            spectrum: Default::default(),
            range: None,
        }],
        materials: vec![
            material(
                "floor",
                MaterialKind::Diffuse {
                    albedo: Vec3::splat(0.8),
                    checker: Some(checker),
                    texture: None,
                    emission: Vec3::ZERO,
                },
            ),
            glass("glass", Glass::Sf11.dispersion()),
        ],
        objects: vec![
            Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y }, material: 0 },
            Object { shape: Shape::Sphere { center: Vec3::new(0.0, 1.0, 0.0), radius: 0.8 }, material: 1 },
        ],
    })
}

/// A warm light panel: a square mesh at `height` facing down, emitting
/// `emission` (half a metre a side, cut into two triangles).
pub fn light_panel(center: Vec3, emission: Vec3) -> (Material, Shape) {
    let h = 0.25;
    let positions = vec![
        center + Vec3::new(-h, 0.0, -h),
        center + Vec3::new(h, 0.0, -h),
        center + Vec3::new(h, 0.0, h),
        center + Vec3::new(-h, 0.0, h),
    ];
    // Wound so that (b − a) × (c − a) points down, toward the scene.
    let shape = Shape::Mesh {
        positions,
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        uvs: Vec::new(),
        normals: Vec::new(),
        tangents: Vec::new(),
    };
    let kind = MaterialKind::Diffuse { albedo: Vec3::splat(0.8), checker: None, texture: None, emission };
    (material("panel", kind), shape)
}

/// The paper's sphere lit by a light panel above it and nothing else: an
/// area light's direct light, soft shadow and caustic. Its two triangles
/// with a budget of one light are a choice by power, drawn anew each pass
/// where the view paths are per pass ([`prismatic_core::plan::drawn_triangles`]).
pub fn panel_lit_sphere() -> PreparedScene {
    let mut scene = glass_sphere().scene;
    scene.lights.clear();
    // A round floor: photons that graze the sphere and would land tens of
    // metres away (where an ulp at the start has grown past the parity
    // tolerances) leave the scene instead.
    scene.objects[0].shape = Shape::Disk { center: Vec3::ZERO, normal: Vec3::Y, radius: 3.0, inner_radius: 0.0 };
    // A panel lights the ball from every side, so many of its photons run
    // round inside it by internal reflection, where an emission direction
    // one ulp apart (lavapipe's) grows past the parity tolerances after
    // four bounces or more; three keep the caustic's paths (in, out, floor).
    scene.render.max_depth = 3;
    scene.render.area_lights = 1;
    let (panel, shape) = light_panel(Vec3::new(-0.6, 3.0, -0.2), Vec3::splat(50.0));
    scene.objects.push(Object { shape, material: scene.materials.len() });
    scene.materials.push(panel);
    prepared(scene)
}

/// The paper's sphere with indirect light: photons that bounce off the
/// floor (and off the floor again after the glass) besides its caustic.
pub fn sphere_with_indirect_light() -> PreparedScene {
    let mut scene = glass_sphere().scene;
    // A round floor, so that bounced photons end within the parity
    // tolerances' reach (an infinite floor sends some tens of metres).
    scene.objects[0].shape = Shape::Disk { center: Vec3::ZERO, normal: Vec3::Y, radius: 3.0, inner_radius: 0.0 };
    scene.render.indirect_photons = 8_000;
    scene.render.max_depth = 4;
    prepared(scene)
}

/// The paper's sphere under a sky of 16 × 8 texels (blue above the
/// horizon, a bright sun low in the west, dark below) and nothing else, cut
/// into 8 suns: their direct light, shadows and caustics, and light
/// bounced off the floor (so that the suns' beams cover the floor and
/// their projection maps aim at the ball), drawn anew each pass where the
/// view paths are per pass.
pub fn sky_lit_sphere() -> PreparedScene {
    let mut scene = sphere_with_indirect_light().scene;
    scene.render.indirect_photons = 2_000;
    scene.render.max_depth = 3;
    scene.render.environment_lights = 8;
    let (w, h) = (16, 8);
    let texels = (0..w * h).map(|i| match (i % w, i / w) {
        (3, 2) => Vec3::new(60.0, 50.0, 40.0),
        (_, y) if y < h / 2 => Vec3::new(0.5, 0.6, 0.9),
        _ => Vec3::splat(0.05),
    });
    let map = EnvironmentMap { name: "sky".into(), width: w, height: h, texels: texels.collect::<Vec<_>>().into() };
    scene.lights = vec![Light::Environment { map, strength: 1.0, rotation_deg: 20.0, spectrum: Default::default() }];
    prepared(scene)
}

/// The paper's sphere in amber glass: Beer–Lambert absorption on the
/// photon paths and on the view rays through it.
pub fn coloured_glass_sphere() -> PreparedScene {
    let mut scene = glass_sphere().scene;
    let MaterialKind::Dielectric { attenuation, .. } = &mut scene.materials[1].kind else {
        unreachable!("material 1 is the glass")
    };
    *attenuation = Some(Attenuation { color: Vec3::new(0.95, 0.6, 0.25), distance: 1.0 });
    prepared(scene)
}

/// The paper's sphere over a textured floor mesh (a coloured 8×8 image,
/// bilinear, tiled three times with mirrored rows): the texture reaches
/// the caustic through the visible points' weights. The sphere wears a
/// film (a 300 nm coating of index 2.4), so every suite also compares the
/// film's reflectance at each path's wavelength.
pub fn textured_floor() -> PreparedScene {
    let mut scene = glass_sphere().scene;
    let MaterialKind::Dielectric { film, .. } = &mut scene.materials[1].kind else {
        unreachable!("the sphere is glass")
    };
    *film = Some(ThinFilm::new(2.4, 300.0));
    let texels: Vec<u32> =
        (0..64u32).map(|i| (40 + 25 * (i % 8)) | (230 - 25 * (i / 8)) << 8 | ((i * 37) % 256) << 16).collect();
    let sampler = Sampler { filter: Filter::Linear, wrap_u: Wrap::Repeat, wrap_v: Wrap::MirroredRepeat };
    let texture = Texture { name: "tiles".into(), width: 8, height: 8, texels: texels.into(), sampler };
    scene.materials[0].kind =
        MaterialKind::Diffuse { albedo: Vec3::splat(0.9), checker: None, texture: Some(texture), emission: Vec3::ZERO };
    let corners = [(-4.0, -4.0), (4.0, -4.0), (4.0, 4.0), (-4.0, 4.0)];
    scene.objects[0].shape = Shape::Mesh {
        positions: corners.iter().map(|&(x, z)| Vec3::new(x, 0.0, z)).collect(),
        triangles: vec![[0, 2, 1], [0, 3, 2]],
        uvs: corners.iter().map(|&(x, z)| glam::Vec2::new(x + 4.0, z + 4.0) * (3.0 / 8.0)).collect(),
        normals: Vec::new(),
        tangents: Vec::new(),
    };
    prepared(scene)
}

/// A beam through a 60° prism of dense flint, fanned onto a wall the camera
/// faces, under a ceiling that catches what the prism reflects.
pub fn prism() -> PreparedScene {
    let h = 3f32.sqrt();
    prepared(Scene {
        render: settings(40, 4_000, 0.1),
        camera: Camera {
            position: Vec3::new(-1.0, 1.0, 7.0),
            look_at: Vec3::new(5.0, -2.0, 0.0),
            up: Vec3::Y,
            fov_deg: 50.0,
        },
        // At 60° incidence on the left face's middle: out of the right face
        // about 66° lower, onto the wall near y = −2.4.
        lights: vec![Light::Beam {
            position: Vec3::new(-3.96, -1.13, 0.0),
            direction: Vec3::new(0.866, 0.5, 0.0),
            radius: 0.15,
            power: 5.0,
            spectrum: Default::default(),
        }],
        materials: vec![glass("flint", Glass::Sf11.dispersion()), diffuse("wall", 0.8)],
        objects: vec![
            Object {
                shape: Shape::Prism {
                    vertices: [Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, -1.0), Vec3::new(0.0, h, -1.0)],
                    extrude: Vec3::new(0.0, 0.0, 2.0),
                },
                material: 0,
            },
            Object { shape: Shape::Plane { point: Vec3::new(5.0, 0.0, 0.0), normal: Vec3::NEG_X }, material: 1 },
            // The left face reflects the beam straight up, parallel to the
            // wall: without a ceiling it met the wall only by rounding, some
            // 4·10⁵ units up, where an NVIDIA GPU's few ulps put 16 % of the
            // photons 0.2 % apart (docs `measurements/gpu.md`).
            Object { shape: Shape::Plane { point: Vec3::new(0.0, 4.0, 0.0), normal: Vec3::NEG_Y }, material: 1 },
        ],
    })
}

/// A beam folded by a mirror onto a floor: a caustic without dispersion.
pub fn mirror() -> PreparedScene {
    prepared(Scene {
        render: settings(32, 3_000, 0.15),
        camera: Camera {
            position: Vec3::new(0.0, 6.0, 4.0),
            look_at: Vec3::new(0.0, 0.0, 0.0),
            up: Vec3::Y,
            fov_deg: 50.0,
        },
        lights: vec![Light::Beam {
            position: Vec3::new(-3.0, 2.0, 0.0),
            direction: Vec3::X,
            radius: 0.4,
            power: 2.0,
            spectrum: Default::default(),
        }],
        materials: vec![diffuse("floor", 0.7), material("mirror", MaterialKind::Mirror)],
        objects: vec![
            Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y }, material: 0 },
            Object {
                shape: Shape::Disk {
                    center: Vec3::new(0.0, 2.0, 0.0),
                    normal: Vec3::new(-1.0, -1.0, 0.0),
                    radius: 0.8,
                    inner_radius: 0.0,
                },
                material: 1,
            },
        ],
    })
}

/// The mirror's beam folded instead by a square mirror whose normal map
/// ripples (16×16 texels of sine slopes, read bilinearly and repeated
/// twice across): a normal map's tilts in caustic photons and in view.
pub fn rippled_mirror() -> PreparedScene {
    let mut scene = mirror().scene;
    let slope = |k: u32, waves: f32| 0.3 * (std::f32::consts::TAU * waves * (k as f32 + 0.5) / 16.0).sin();
    let byte = |x: f32| ((x + 1.0) * 0.5 * 255.0).round() as u32;
    let texels = (0..16 * 16)
        .map(|k| {
            let n = Vec3::new(-slope(k % 16, 2.0), -slope(k / 16, 3.0), 1.0).normalize();
            byte(n.x) | byte(n.y) << 8 | byte(n.z) << 16
        })
        .collect();
    let sampler = Sampler { filter: Filter::Linear, wrap_u: Wrap::Repeat, wrap_v: Wrap::Repeat };
    let texture = Texture { name: "ripples".into(), width: 16, height: 16, texels, sampler };
    scene.materials[1].normal_map = Some(NormalMap { texture, scale: 1.0 });
    // Facing (−1, −1, 0) at (0, 2, 0), where the disc was: u along `a`, v along `b`.
    let (center, a, b) = (Vec3::new(0.0, 2.0, 0.0), Vec3::new(-1.0, 1.0, 0.0).normalize(), Vec3::Z);
    let corners = [(-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (1.0, -1.0)];
    scene.objects[1].shape = Shape::Mesh {
        positions: corners.iter().map(|&(s, t)| center + (a * s + b * t) * 0.8).collect(),
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        uvs: corners.iter().map(|&(s, t)| glam::Vec2::new(s + 1.0, t + 1.0)).collect(),
        normals: Vec::new(),
        tangents: Vec::new(),
    };
    prepared(scene)
}

/// The mirror's beam folded by a rough gold square instead (its colour
/// scaled by a texture of four tiles, gold, grey, rose and pale) onto a
/// round floor, the gold worn through to a diffuse base texel by texel
/// (a metalness of 0.9 times a map's; the base under a dielectric's
/// coloured specular layer whose weight and colour maps vary it) under a
/// film whose thickness a map
/// varies, beside a polished ball of measured
/// copper under a patchy film of its oxide (a factor of 0.6), with
/// indirect light: metals' facets, coloured Fresnel texel by texel, a
/// blended metal's two parts and its base's layer, a film map's films and a partial film's over a complex index,
/// in caustic and indirect photons and in view.
pub fn metals() -> PreparedScene {
    let mut scene = mirror().scene;
    let metal = |name: &str, color: MetalColor, roughness: f32, texture: Option<Texture>, film: Option<ThinFilm>| {
        material(name, MaterialKind::Metal { color, roughness, texture, film, metalness: Metalness::WHOLE })
    };
    let texels = [[255, 255, 255], [200, 200, 200], [255, 190, 200], [240, 250, 255]];
    let tiles = Texture {
        name: "tiles".into(),
        width: 2,
        height: 2,
        texels: texels.iter().map(|&[r, g, b]| r | g << 8 | b << 16).collect::<Vec<u32>>().into(),
        sampler: Sampler { filter: Filter::Nearest, wrap_u: Wrap::Repeat, wrap_v: Wrap::Repeat },
    };
    scene.materials[1] = metal("gold", MetalColor::Rgb(Vec3::new(1.0, 0.766, 0.336)), 0.3, Some(tiles), None);
    // Worn through in places: 90 % metal times the blue of a roughness map
    // (whole, a third, none, most), its green keeping the roughness.
    let MaterialKind::Metal { metalness, .. } = &mut scene.materials[1].kind else { unreachable!("gold") };
    // The base a dielectric's coloured specular layer covers.
    let layer = SpecularLayer::gltf(1.6, 0.8, Vec3::new(1.0, 0.9, 30.0));
    *metalness = Metalness { factor: 0.9, mapped: true, layer };
    // Under a film of an oxide, 120 to 350 nm thick across the tiles.
    let MaterialKind::Metal { film, .. } = &mut scene.materials[1].kind else { unreachable!("gold") };
    *film = Some(ThinFilm { factor: 0.7, ..ThinFilm::new(1.8, 350.0) });
    scene.materials[1].film_map = Some(FilmMap {
        thickness: Some(Texture {
            name: "tint".into(),
            width: 2,
            height: 2,
            texels: [0u32, 90, 180, 255].iter().map(|&g| g << 8).collect::<Vec<u32>>().into(),
            sampler: Sampler { filter: Filter::Linear, wrap_u: Wrap::Repeat, wrap_v: Wrap::Repeat },
        }),
        min_nm: 120.0,
        factor: None,
    });
    // Its layer glossier in places, and tinted across the tiles (blue
    // clipping where the tint is strong).
    scene.materials[1].specular_map = Some(SpecularMap {
        weight: Some(Texture {
            name: "gloss".into(),
            width: 2,
            height: 2,
            texels: [255u32, 40, 0, 160].iter().map(|&r| r | 7 << 8).collect::<Vec<u32>>().into(),
            sampler: Sampler { filter: Filter::Linear, wrap_u: Wrap::Repeat, wrap_v: Wrap::Repeat },
        }),
        color: Some(Texture {
            name: "sheen".into(),
            width: 2,
            height: 2,
            texels: [[255u32, 255, 255], [40, 200, 90], [255, 120, 0], [10, 10, 255]]
                .iter()
                .map(|&[r, g, b]| r | g << 8 | b << 16)
                .collect::<Vec<u32>>()
                .into(),
            sampler: Sampler { filter: Filter::Nearest, wrap_u: Wrap::ClampToEdge, wrap_v: Wrap::Repeat },
        }),
        color_f0: SpecularLayer::unclipped_f0(1.6, Vec3::new(1.0, 0.9, 30.0)),
    });
    scene.materials[1].roughness_map = Some(Texture {
        name: "worn".into(),
        width: 2,
        height: 2,
        texels: [255u32, 85, 0, 200].iter().map(|&b| 255 << 8 | b << 16).collect::<Vec<u32>>().into(),
        sampler: Sampler { filter: Filter::Nearest, wrap_u: Wrap::Repeat, wrap_v: Wrap::Repeat },
    });
    // Copper under 90 nm of its oxide (index 2.5) over 60 % of it.
    let tarnish = ThinFilm { factor: 0.6, ..ThinFilm::new(2.5, 90.0) };
    scene.materials.push(metal("copper", MetalColor::Measured(NamedMetal::Copper), 0.0, None, Some(tarnish)));
    // Facing (−1, −1, 0) at (0, 2, 0), where the mirror's disc was; its tiles meet at the beam's axis.
    let (center, a, b) = (Vec3::new(0.0, 2.0, 0.0), Vec3::new(-1.0, 1.0, 0.0).normalize(), Vec3::Z);
    let corners = [(-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (1.0, -1.0)];
    scene.objects[1].shape = Shape::Mesh {
        positions: corners.iter().map(|&(s, t)| center + (a * s + b * t) * 0.8).collect(),
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        uvs: corners.iter().map(|&(s, t)| glam::Vec2::new(s + 1.0, t + 1.0) * 0.5).collect(),
        normals: Vec::new(),
        tangents: Vec::new(),
    };
    scene.objects[0].shape = Shape::Disk { center: Vec3::ZERO, normal: Vec3::Y, radius: 4.0, inner_radius: 0.0 };
    scene.objects.push(Object { shape: Shape::Sphere { center: Vec3::new(1.2, 0.5, 1.0), radius: 0.5 }, material: 2 });
    scene.render.indirect_photons = 2_000;
    scene.render.max_depth = 4;
    prepared(scene)
}

/// The paper's sphere frosted (roughness 0.3), beside a frosted blue
/// sheet (roughness 0.5, scaled across it by a roughness map from
/// polished to whole) standing in the spot's cone: rough glass's facets
/// and Fresnel per band in photons and view rays, its highlights of the
/// spot on both sides, a tinted sheet's crossings off its facets, and
/// facets that change with the texel.
pub fn frosted_glass() -> PreparedScene {
    let mut scene = glass_sphere().scene;
    let MaterialKind::Dielectric { roughness, .. } = &mut scene.materials[1].kind else {
        unreachable!("the sphere is glass")
    };
    *roughness = 0.3;
    let sheet = MaterialKind::Dielectric {
        dispersion: Dispersion::Constant(1.5),
        outside: Dispersion::Constant(1.0),
        attenuation: Some(Attenuation { color: Vec3::new(0.5, 0.7, 0.95), distance: 1.0 }),
        thin: true,
        film: None,
        roughness: 0.5,
    };
    // Eight stripes along u, green 0 (polished) to 255, blended between.
    let texels = (0..8u32).map(|k| (k * 255 / 7) << 8).collect();
    let sampler = Sampler { filter: Filter::Linear, wrap_u: Wrap::ClampToEdge, wrap_v: Wrap::ClampToEdge };
    let stripes = Texture { name: "stripes".into(), width: 8, height: 1, texels, sampler };
    scene.materials.push(Material { roughness_map: Some(stripes), ..material("frosted sheet", sheet) });
    let (x, y, z) = (-0.9, [0.0, 2.2], [-1.6, 1.2]);
    let positions =
        vec![Vec3::new(x, y[0], z[0]), Vec3::new(x, y[0], z[1]), Vec3::new(x, y[1], z[1]), Vec3::new(x, y[1], z[0])];
    let square = Shape::Mesh {
        positions,
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        uvs: [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]].map(glam::Vec2::from).to_vec(),
        normals: Vec::new(),
        tangents: Vec::new(),
    };
    scene.objects.push(Object { shape: square, material: 2 });
    prepared(scene)
}

/// A floor and a diffuse ball under a point light: nothing specular, so no
/// caustic photon is traced and the image is its view pass's.
pub fn no_caustics() -> PreparedScene {
    prepared(Scene {
        render: settings(24, 2_000, 0.1),
        camera: Camera { position: Vec3::new(0.0, 2.0, 5.0), look_at: Vec3::ZERO, up: Vec3::Y, fov_deg: 45.0 },
        lights: vec![Light::Point {
            position: Vec3::new(1.0, 4.0, 1.0),
            power: 30.0,
            spectrum: Default::default(),
            range: None,
        }],
        materials: vec![diffuse("floor", 0.7), diffuse("ball", 0.5)],
        objects: vec![
            Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y }, material: 0 },
            Object { shape: Shape::Sphere { center: Vec3::new(0.0, 0.6, 0.0), radius: 0.6 }, material: 1 },
        ],
    })
}

/// The paper's sphere as a closed mesh of `4 · rings²` triangles: every
/// backend's hierarchy traversal (flat facets).
pub fn glass_mesh_sphere(rings: u32) -> PreparedScene {
    let mut scene = glass_sphere().scene;
    scene.objects[1].shape = sphere_mesh(Vec3::new(0.0, 1.0, 0.0), 0.8, rings);
    prepared(scene)
}

/// [`sphere_mesh`] with the sphere's normals at its vertices: it scatters
/// light as the round sphere does, less the rims of its flat facets.
pub fn smooth_sphere_mesh(center: Vec3, radius: f32, rings: u32) -> Shape {
    let Shape::Mesh { positions, triangles, uvs, .. } = sphere_mesh(center, radius, rings) else {
        unreachable!("sphere_mesh is a mesh")
    };
    let normals = positions.iter().map(|p| (*p - center).normalize()).collect();
    Shape::Mesh { positions, triangles, uvs, normals, tangents: Vec::new() }
}

/// A closed sphere mesh, wound outward: `rings` rings of `2 · rings`
/// quads split in two, `4 · rings²` triangles of which the `4 · rings` at
/// the poles have no area (dropped when the scene is prepared).
pub fn sphere_mesh(center: Vec3, radius: f32, rings: u32) -> Shape {
    let segments = 2 * rings;
    let mut positions = Vec::with_capacity(((rings + 1) * segments) as usize);
    for r in 0..=rings {
        let theta = core::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..segments {
            let phi = core::f32::consts::TAU * s as f32 / segments as f32;
            let dir = match r {
                0 => Vec3::Y,
                _ if r == rings => -Vec3::Y,
                _ => Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin()),
            };
            positions.push(center + radius * dir);
        }
    }
    let mut triangles = Vec::with_capacity((2 * rings * segments) as usize);
    for r in 0..rings {
        for s in 0..segments {
            let (a, b) = (r * segments + s, r * segments + (s + 1) % segments);
            let (c, d) = (a + segments, b + segments);
            triangles.extend([[a, b, c], [b, d, c]]);
        }
    }
    Shape::Mesh { positions, triangles, uvs: Vec::new(), normals: Vec::new(), tangents: Vec::new() }
}

/// [`glass_mesh_sphere`] with the sphere's normals at its vertices: every
/// backend's smooth shading.
pub fn smooth_glass_mesh_sphere(rings: u32) -> PreparedScene {
    let mut scene = glass_sphere().scene;
    scene.objects[1].shape = smooth_sphere_mesh(Vec3::new(0.0, 1.0, 0.0), 0.8, rings);
    prepared(scene)
}

/// [`glass_sphere`] lit by every kind of light at once (powers that differ,
/// so a light is chosen by its share), with or without projection maps and
/// with either photon sequence: every branch of emission, for its twin tests.
pub fn lit_by_every_light_kind(projection_maps: bool, sequence: PhotonSequence) -> PreparedScene {
    let mut scene = glass_sphere().scene;
    scene.lights.extend([
        Light::Point { position: Vec3::new(1.0, 4.0, 1.0), power: 25.0, spectrum: Default::default(), range: None },
        // A soft edge from 10° to 35° (glTF's innerConeAngle).
        Light::Spot {
            position: Vec3::new(2.0, 5.0, -1.0),
            direction: Vec3::new(-2.0, -4.0, 1.0),
            cone_deg: 35.0,
            inner_cone_deg: 10.0,
            power: 30.0,
            spectrum: Default::default(),
            range: None,
        },
        Light::Beam {
            position: Vec3::new(-3.0, 1.0, 0.0),
            direction: Vec3::X,
            radius: 0.3,
            power: 10.0,
            spectrum: Default::default(),
        },
        Light::Sun {
            direction: Vec3::new(0.3, -1.0, 0.2),
            irradiance: 2.0,
            spectrum: Default::default(),
            mean_toward: None,
        },
    ]);
    let (panel, shape) = light_panel(Vec3::new(0.8, 3.5, 0.4), Vec3::splat(20.0));
    scene.objects.push(Object { shape, material: scene.materials.len() });
    scene.materials.push(panel);
    scene.render.projection_maps = projection_maps;
    scene.render.photon_sequence = sequence;
    prepared(scene)
}

/// The scenes with caustics, by name.
pub fn with_caustics() -> Vec<(&'static str, PreparedScene)> {
    vec![
        ("glass sphere", glass_sphere()),
        ("smooth glass mesh sphere", smooth_glass_mesh_sphere(12)),
        ("coloured glass sphere", coloured_glass_sphere()),
        ("textured floor", textured_floor()),
        ("prism", prism()),
        ("mirror", mirror()),
        ("rippled mirror", rippled_mirror()),
        ("metals", metals()),
        ("frosted glass", frosted_glass()),
        ("panel-lit sphere", panel_lit_sphere()),
        ("sphere with indirect light", sphere_with_indirect_light()),
        ("sky-lit sphere", sky_lit_sphere()),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sphere_mesh_is_closed_and_wound_outward() {
        let Shape::Mesh { positions, triangles, .. } = sphere_mesh(Vec3::Y, 0.8, 6) else { unreachable!() };
        assert_eq!(triangles.len(), 4 * 36);
        assert_eq!(prismatic_core::model::mesh::open_edge(&positions, &triangles), None);
        for t in prismatic_core::geometry::primitive::mesh_triangles(&positions, &triangles) {
            let centroid = t.v0 + (t.e1 + t.e2) / 3.0;
            assert!(t.normal.dot(centroid - Vec3::Y) > 0.0, "inward triangle at {centroid}");
        }
    }
}
