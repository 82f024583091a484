//! Films that vary over a mesh (glTF's `iridescenceThicknessTexture` and
//! `iridescenceTexture`) on every backend: where a texel's green makes the
//! film min + g (max − min) thick and its red scales the factor, the
//! surface is the surface of that film, on coated glass and on metals.

use crate::roughness_maps::{assert_the_same_images, lit_beside_the_camera};
use prismatic_core::model::dispersion::Dispersion;
use prismatic_core::model::metalness::Metalness;
use prismatic_core::model::scene::{FilmMap, Filter, Material, MaterialKind, Sampler, Texture, ThinFilm, Wrap};
use prismatic_core::{MetalColor, Vec3};
use prismatic_tests::{TRIANGLE_WITH_UVS, one_material_scene_file, prepare, view_through_a_sheet};

/// An image of one texel of these channels, read nearest.
fn texel([r, g, b]: [u8; 3]) -> Texture {
    let texel = u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16;
    let sampler = Sampler { filter: Filter::Nearest, wrap_u: Wrap::Repeat, wrap_v: Wrap::Repeat };
    Texture { name: "iridescence".into(), width: 1, height: 1, texels: vec![texel].into(), sampler }
}

/// A material kind under a film.
type Filmed = fn(ThinFilm) -> MaterialKind;

/// A thin coated sheet of glass under `film`.
fn coated_sheet(film: ThinFilm) -> MaterialKind {
    MaterialKind::Dielectric {
        dispersion: Dispersion::Constant(1.5),
        outside: Dispersion::Constant(1.0),
        attenuation: None,
        thin: true,
        film: Some(film),
        roughness: 0.0,
    }
}

/// A slightly rough silver-grey metal under `film` (its highlight of the
/// point light shows the film's colour).
fn filmed_metal(film: ThinFilm) -> MaterialKind {
    let color = MetalColor::Rgb(Vec3::splat(0.9));
    MaterialKind::Metal { color, roughness: 0.3, texture: None, film: Some(film), metalness: Metalness::WHOLE }
}

/// Also where the film's own (maximum) thickness is 0 and the map's
/// minimum is not (glTF allows it): the film is min (1 − g) thick, not
/// dropped as bare.
#[test]
fn in_view_a_uniform_film_map_is_the_film_it_scales_to() {
    let [r, g] = [102u8, 153u8];
    for (film, min_nm) in
        [(ThinFilm { factor: 0.8, ..ThinFilm::new(1.38, 500.0) }, 100.0), (ThinFilm::new(1.38, 0.0), 250.0)]
    {
        let map = FilmMap { thickness: Some(texel([0, g, 0])), min_nm, factor: Some(texel([r, 0, 0])) };
        let scaled = ThinFilm {
            thickness_nm: min_nm + f32::from(g) / 255.0 * (film.thickness_nm - min_nm),
            factor: film.factor * (f32::from(r) / 255.0),
            ..film
        };
        for (case, kind) in [("coated sheet", coated_sheet as Filmed), ("filmed metal", filmed_metal)] {
            let case = format!("{case} of {} nm over {min_nm} nm", film.thickness_nm);
            let seen = |material: Material| prepare(lit_beside_the_camera(view_through_a_sheet(material).scene));
            let mapped = Material { film_map: Some(map.clone()), ..Material::new("filmed", kind(film)) };
            assert_the_same_images(&case, &seen(mapped), &seen(Material::new("filmed", kind(scaled))), 1e-3);
        }
    }
}

/// A scene file varies a film with `film_thickness_map` (green, from
/// `film_min_nm` to `film_thickness_nm`) and `film_factor_map` (red
/// scales `film_factor`), images beside it read as linear values; a map
/// without a film, or a minimum without a thickness map, is refused with
/// its key.
#[test]
fn scene_files_give_films_maps() {
    let dir = tempfile::tempdir().unwrap();
    image::RgbImage::from_raw(1, 1, vec![51, 204, 0]).unwrap().save(dir.path().join("soap.png")).unwrap();
    let check = |material: &str| one_material_scene_file(dir.path(), material, TRIANGLE_WITH_UVS);
    let glass = "kind = \"dielectric\"\nior = 1.5\nthin = true";
    let filmed = format!(
        "{glass}\nfilm_thickness_nm = 600\nfilm_thickness_map = \"soap.png\"\nfilm_min_nm = 150\nfilm_factor_map = \"soap.png\""
    );
    let doc = check(&filmed).unwrap_or_else(|e| panic!("{e}"));
    let map = doc.scene.materials[0].film_map.as_ref().expect("a film map");
    assert_eq!(map.min_nm, 150.0);
    let texels = |t: &Option<Texture>| t.as_ref().expect("a map").texels[0];
    assert_eq!((texels(&map.thickness), texels(&map.factor)), (51 | 204 << 8, 51 | 204 << 8));
    for (material, key, reason) in [
        (format!("{glass}\nfilm_thickness_map = \"soap.png\""), "material.m.film_thickness_map", "has none"),
        (
            format!("{glass}\nfilm_thickness_nm = 600\nfilm_min_nm = 150"),
            "material.m.film_min_nm",
            "no film_thickness_map",
        ),
        (format!("{glass}\nfilm_thickness_nm = 600\nfilm_factor_map = \"none.png\""), "material.m.film_factor_map", ""),
    ] {
        let e = check(&material).map(|_| ()).unwrap_err();
        assert!(e.key == key && e.reason.contains(reason), "{material}: {e}");
    }
}
