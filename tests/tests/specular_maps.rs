//! Specular layers that vary over a mesh (glTF's `specularTexture` and
//! `specularColorTexture`) on every backend: where a texel's weight w
//! (the weight map's red, linear) and colour c (the colour map, sRGB)
//! make the layer F0 = min(F0_colour · c, 1) · w and F90 = w, the surface
//! is the surface of that layer, in view and for photons.

use crate::roughness_maps::{assert_the_same_images, beam_at_a_square, lit_beside_the_camera};
use prismatic_core::geometry::texture::srgb_to_linear;
use prismatic_core::model::metalness::{Metalness, SpecularLayer};
use prismatic_core::model::scene::{Filter, Material, MaterialKind, Sampler, SpecularMap, Texture, ThinFilm, Wrap};
use prismatic_core::{MetalColor, PreparedScene, Vec3};
use prismatic_tests::backends::{every_backend, trace};
use prismatic_tests::{TRIANGLE_WITH_UVS, one_material_scene_file, prepare, view_through_a_sheet};

/// An image of one texel of these channels, read nearest.
fn texel([r, g, b]: [u8; 3]) -> Texture {
    let texel = u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16;
    let sampler = Sampler { filter: Filter::Nearest, wrap_u: Wrap::Repeat, wrap_v: Wrap::Repeat };
    Texture { name: "specular".into(), width: 1, height: 1, texels: vec![texel].into(), sampler }
}

/// A layered surface as glTF's factors make it: base colour `color`,
/// metalness `m`, roughness `roughness`, under the layer of index `ior`,
/// weight `weight` and colour `tint` (and `film` on it).
struct Layered {
    color: Vec3,
    m: f32,
    roughness: f32,
    film: Option<ThinFilm>,
    ior: f32,
    weight: f32,
    tint: Vec3,
}

impl Layered {
    /// The material with the layer of `weight` and `tint`.
    fn material(&self, weight: f32, tint: Vec3, map: Option<SpecularMap>) -> Material {
        let layer = SpecularLayer::gltf(self.ior, weight, tint);
        let metalness = Metalness { layer, ..Metalness::plain(self.m) };
        let kind = MaterialKind::Metal {
            color: MetalColor::Rgb(self.color),
            roughness: self.roughness,
            texture: None,
            film: self.film,
            metalness,
        };
        Material { specular_map: map, ..Material::new("layered", kind) }
    }

    /// Its material under one texel of weight `w` (the weight map's red)
    /// and one of colour `c` (sRGB).
    fn mapped(&self, w: u8, c: [u8; 3]) -> Material {
        let map = SpecularMap {
            weight: Some(texel([w, 0, 0])),
            color: Some(texel(c)),
            color_f0: SpecularLayer::unclipped_f0(self.ior, self.tint),
        };
        self.material(self.weight, self.tint, Some(map))
    }

    /// The material whose factors are what the texels make them.
    fn scaled(&self, w: u8, c: [u8; 3]) -> Material {
        let colour = Vec3::from(c.map(|x| srgb_to_linear(u32::from(x))));
        self.material(self.weight * f32::from(w) / 255.0, self.tint * colour, None)
    }
}

/// A plastic under a polished layer; a half-metal under a rough, filmed
/// layer whose colour clips (20 · F0(2) > 1 in blue: the map scales the
/// colour before the clip); a weight of 0 (no layer there).
fn cases() -> [(&'static str, Layered, u8, [u8; 3]); 3] {
    let plastic = Layered {
        color: Vec3::new(0.2, 0.5, 0.8),
        m: 0.0,
        roughness: 0.0,
        film: None,
        ior: 1.5,
        weight: 0.8,
        tint: Vec3::new(1.0, 0.5, 0.25),
    };
    let filmed = Layered {
        color: Vec3::new(0.9, 0.6, 0.3),
        m: 0.5,
        roughness: 0.4,
        film: Some(ThinFilm::new(1.38, 300.0)),
        ior: 2.0,
        weight: 1.0,
        tint: Vec3::new(1.0, 0.5, 20.0),
    };
    let bare = Layered { weight: 0.5, ..plastic };
    [
        ("plastic", plastic, 153, [200, 120, 60]),
        ("filmed half-metal", filmed, 230, [90, 255, 140]),
        ("bare", bare, 0, [255; 3]),
    ]
}

/// In view, a surface under uniform specular maps is the surface of the
/// layer they scale it to.
#[test]
fn in_view_uniform_specular_maps_are_the_layer_they_scale_to() {
    for (case, layered, w, c) in cases() {
        let seen = |material: Material| prepare(lit_beside_the_camera(view_through_a_sheet(material).scene));
        assert_the_same_images(case, &seen(layered.mapped(w, c)), &seen(layered.scaled(w, c)), 1e-3);
    }
}

/// The flux a beam at the square of `material` (head on) sends back to
/// the wall behind the beam, on each backend.
fn reflected_flux(material: Material) -> Vec<(String, f64)> {
    let scene: PreparedScene = beam_at_a_square(material, 0.5, 20_000);
    every_backend()
        .into_iter()
        .map(|mut backend| {
            let map = trace(backend.as_mut(), &scene);
            let wall = map.photons.iter().filter(|p| p.position[0] < -2.9);
            (backend.name().to_string(), wall.map(|p| f64::from(p.flux)).sum())
        })
        .collect()
}

/// Photons reflect off a mapped layer with the layer's share and Fresnel
/// there: the flux a half-metal sends back (its metal's and its layer's)
/// equals that of the layer the maps scale it to. (A plastic's layer
/// casts no caustic: a surface without metal does not focus light.)
#[test]
fn photons_reflect_off_a_mapped_layer_as_off_the_layer_it_scales_to() {
    for (case, layered, w, c) in cases() {
        let layered = Layered { m: layered.m.max(0.5), ..layered };
        let (mapped, scaled) = (reflected_flux(layered.mapped(w, c)), reflected_flux(layered.scaled(w, c)));
        for ((name, got), (_, want)) in mapped.iter().zip(&scaled) {
            assert!(*want > 0.0, "{case}: {name}: nothing reflected");
            assert!((got / want - 1.0).abs() < 1e-4, "{case}: {name}: {got} where {want}");
        }
    }
}

/// A scene file varies a layer with `specular_map` (red scales
/// `specular`) and `specular_color_map` (sRGB, scales `specular_color`
/// before the clip), images beside it; a map without a layer is refused
/// with its key.
#[test]
fn scene_files_give_specular_layers_maps() {
    let dir = tempfile::tempdir().unwrap();
    image::RgbImage::from_raw(1, 1, vec![51, 204, 0]).unwrap().save(dir.path().join("gloss.png")).unwrap();
    let check = |material: &str| one_material_scene_file(dir.path(), material, TRIANGLE_WITH_UVS);
    let plastic = "kind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]";
    let layered = format!(
        "{plastic}\nspecular = 0.9\nspecular_ior = 2\nspecular_color = [1, 2, 30]\n\
         specular_map = \"gloss.png\"\nspecular_color_map = \"gloss.png\""
    );
    let doc = check(&layered).unwrap_or_else(|e| panic!("{e}"));
    let material = &doc.scene.materials[0];
    let map = material.specular_map.as_ref().expect("a specular map");
    let texels = |t: &Option<Texture>| t.as_ref().expect("a map").texels[0];
    assert_eq!((texels(&map.weight), texels(&map.color)), (51 | 204 << 8, 51 | 204 << 8));
    assert!((map.color_f0 - Vec3::new(1.0, 2.0, 30.0) / 9.0).abs().max_element() < 1e-6, "{}", map.color_f0);
    let metal =
        "kind = \"metal\"\ncolor = [0.9, 0.8, 0.7]\nmetalness = 0.5\nspecular = 1\nspecular_map = \"gloss.png\"";
    assert!(check(metal).unwrap_or_else(|e| panic!("{e}")).scene.materials[0].specular_map.is_some());
    for (material, key, reason) in [
        (format!("{plastic}\nspecular_map = \"gloss.png\""), "material.m.specular_map", "has none"),
        (format!("{plastic}\nspecular_color_map = \"gloss.png\""), "material.m.specular_color_map", "give specular"),
        (
            "kind = \"metal\"\ncolor = \"gold\"\nspecular = 1\nspecular_map = \"gloss.png\"".to_string(),
            "material.m.specular_map",
            "has none",
        ),
        (format!("{plastic}\nspecular = 1\nspecular_map = \"none.png\""), "material.m.specular_map", ""),
    ] {
        let e = check(&material).map(|_| ()).unwrap_err();
        assert!(e.key == key && e.reason.contains(reason), "{material}: {e}");
    }
}
