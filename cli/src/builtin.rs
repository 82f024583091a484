//! The built-in scenes, compiled in from `scenes/*.toml`.

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

/// Every built-in scene; the first is the default.
pub const BUILTIN_SCENES: [BuiltinScene; 4] = [
    BuiltinScene {
        name: "sphere",
        description: "the paper's glass sphere on a checkered floor under a spot light (7-band caustic)",
        source: include_str!("../../scenes/sphere.toml"),
    },
    BuiltinScene {
        name: "prism",
        description: "white light through a 60-degree prism, fanned into a spectrum on a wall",
        source: include_str!("../../scenes/prism.toml"),
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
];

/// The built-in scene called `name`.
pub fn find(name: &str) -> Option<&'static BuiltinScene> {
    BUILTIN_SCENES.iter().find(|s| s.name == name)
}
