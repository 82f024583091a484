//! The built-in scenes: scene files compiled in from `scenes/*.toml`, and
//! scenes the project generates as glTF.

/// A built-in scene: its name, a one-line description and its TOML source.
#[derive(Clone, Copy, Debug)]
pub struct BuiltinScene {
    /// Name used on the command line.
    pub name: &'static str,
    /// What it shows.
    pub description: &'static str,
    /// The scene file.
    pub source: &'static str,
}

/// Every built-in scene file.
pub const BUILTIN_SCENES: [BuiltinScene; 11] = [
    BuiltinScene {
        name: "spectrum",
        description: "a prism's spectrum on a wall behind the paper's glass sphere and its caustic (the default)",
        source: include_str!("../../scenes/spectrum.toml"),
    },
    BuiltinScene {
        name: "caustic",
        description: "the sphere scene seen close up: the caustic's rim split into its colours",
        source: include_str!("../../scenes/caustic.toml"),
    },
    BuiltinScene {
        name: "sphere",
        description: "the paper's glass sphere on a checkered floor under a spot light (7-band caustic)",
        source: include_str!("../../scenes/sphere.toml"),
    },
    BuiltinScene {
        name: "softbox",
        description: "a flint glass ball under a photographer's softbox: soft shadow, the box's coloured, blurred caustic",
        source: include_str!("../../scenes/softbox.toml"),
    },
    BuiltinScene {
        name: "room",
        description: "a Cornell box lit by its ceiling lamp: light bounced off the red and green walls, a flint ball's caustic",
        source: include_str!("../../scenes/room.toml"),
    },
    BuiltinScene {
        name: "prism",
        description: "white light through a 60-degree prism, fanned into a spectrum on a wall",
        source: include_str!("../../scenes/prism.toml"),
    },
    BuiltinScene {
        name: "lamps",
        description: "white light, a 2700 K bulb and a mercury lamp through one prism: a spectrum, a reddened one, lines",
        source: include_str!("../../scenes/lamps.toml"),
    },
    BuiltinScene {
        name: "recombine",
        description: "a second, inverted prism makes the bands parallel again: white downstream",
        source: include_str!("../../scenes/recombine.toml"),
    },
    BuiltinScene {
        name: "rainbow",
        description: "a beam through a hole in a screen onto a water sphere: primary and secondary bows",
        source: include_str!("../../scenes/rainbow.toml"),
    },
    BuiltinScene {
        name: "coated",
        description: "a glass ball under a thin-film coating: reflections and rings in thin-film colours, a tinted caustic",
        source: include_str!("../../scenes/coated.toml"),
    },
    BuiltinScene {
        name: "frosted",
        description: "a polished and a frosted flint ball: a sharp caustic beside a soft glow with coloured rims",
        source: include_str!("../../scenes/frosted.toml"),
    },
];

/// What `render` and `photons` render when no scene is named.
pub const DEFAULT_SCENE: &str = "spectrum";

/// The built-in scene called `name`.
pub fn find(name: &str) -> Option<&'static BuiltinScene> {
    BUILTIN_SCENES.iter().find(|s| s.name == name)
}

/// A built-in scene the project writes as glTF and reads back.
#[derive(Clone, Copy, Debug)]
pub struct GeneratedScene {
    /// Name used on the command line.
    pub name: &'static str,
    /// What it shows.
    pub description: &'static str,
    /// The glTF document.
    pub document: fn() -> crate::gltf_write::GltfDocument,
    /// Its render settings (glTF has none).
    pub settings: fn(&mut prismatic_core::model::scene::RenderSettings),
}

/// The generated built-in scenes.
pub const GENERATED_SCENES: [GeneratedScene; 4] = [
    GeneratedScene {
        name: "dispersion-test",
        description: "glTF: a grid of prisms, index 1.0 to 2.42 by row, KHR_materials_dispersion 0 to 5 by column",
        document: crate::dispersion_test::document,
        settings: crate::dispersion_test::settings,
    },
    GeneratedScene {
        name: "sunlit-glass",
        description: "glTF: amber and green glass and a flint prism in the sun on a tiled floor before a wall",
        document: crate::sunlit_glass::document,
        settings: crate::sunlit_glass::settings,
    },
    GeneratedScene {
        name: "ring",
        description: "glTF: a gold ring in low sun with the cusped caustic of its inner wall, a rough copper and a polished silver ball",
        document: crate::ring::document,
        settings: crate::ring::settings,
    },
    GeneratedScene {
        name: "pool",
        description: "glTF: the sun through rippled water (a normal map) draws a net of bright lines on a tiled floor",
        document: crate::pool::document,
        settings: crate::pool::settings,
    },
];

/// The generated built-in scene called `name`.
pub fn find_generated(name: &str) -> Option<&'static GeneratedScene> {
    GENERATED_SCENES.iter().find(|s| s.name == name)
}

/// Every built-in scene's name.
pub fn names() -> Vec<&'static str> {
    BUILTIN_SCENES.iter().map(|s| s.name).chain(GENERATED_SCENES.iter().map(|s| s.name)).collect()
}
