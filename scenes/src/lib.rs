//! The standard scenes of `embedded-raytracer` (`scenes/*.toml`), for the host tools,
//! the lab and any other front end: their names and texts (`src/list.rs`, re-exported
//! here) and loading one by name with the host's capacities.
//!
//! Nothing here is part of the library's API; the library's own tests read `list.rs`
//! alone (`#[path]`), never this crate.

mod list;
pub use list::*;

use embedded_raytracer::scene_file::{self, SceneFile};

/// The reflection depth a host tool's scene type can trace: every `max_depth` a scene
/// file may ask for.
pub const MAX_DEPTH: usize = embedded_raytracer::MAX_DEPTH as usize;

/// A scene file loaded with every capacity a host tool has.
pub type FullSceneFile = SceneFile<MAX_SPHERES, MAX_LIGHTS, MAX_PLANES, MAX_DEPTH>;

/// The path of scene file `name` in this checkout (`scenes/NAME.toml`).
pub fn path(name: &str) -> String {
    format!("{}/{name}.toml", env!("CARGO_MANIFEST_DIR"))
}

/// Standard spheres-only scene `name` ([`SCENES`]), loaded from its file (panics with
/// the loader's message if the file is broken: the standard scenes are part of the
/// repository).
pub fn load(name: &str) -> SceneFile<MAX_SPHERES> {
    scene_file::load(path(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// Any standard scene `name` ([`SCENES`] or [`FEATURE_SCENES`]), loaded with the full
/// capacities (panics with the loader's message if the file is broken).
pub fn load_full(name: &str) -> FullSceneFile {
    scene_file::load(path(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// The method flags of the host tools' usage, every choice listed from the method's
/// own tables: `[--stepping a|b|c] [--sphere-test …] [--sqrt …]`.
pub fn method_flags() -> String {
    use embedded_raytracer::{SphereTest, Sqrt, Stepping};
    format!(
        "[--stepping {}] [--sphere-test {}] [--sqrt {}]",
        Stepping::NAMES.join("|"),
        SphereTest::NAMES.join("|"),
        Sqrt::NAMES.join("|")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`TEXTS`] holds every scene file of the folder, each the file's text, and every
    /// standard scene.
    #[test]
    fn texts_are_the_folders_files() {
        let mut files: Vec<String> = std::fs::read_dir(env!("CARGO_MANIFEST_DIR"))
            .unwrap()
            .filter_map(|e| {
                let name = e.unwrap().file_name().into_string().unwrap();
                name.strip_suffix(".toml").map(str::to_string)
            })
            .filter(|name| name != "Cargo")
            .collect();
        files.sort();
        let mut names: Vec<String> = TEXTS.iter().map(|(n, _)| n.to_string()).collect();
        names.sort();
        assert_eq!(names, files);
        for (name, text) in TEXTS {
            assert_eq!(std::fs::read_to_string(path(name)).unwrap(), text, "{name}");
        }
        for name in SCENES.iter().chain(&FEATURE_SCENES) {
            assert!(text(name).is_some(), "{name}");
        }
        assert_eq!(text("nothing"), None);
    }

    /// Every standard scene loads with the capacities its list names (the spheres-only
    /// ones as `Scene<MAX_SPHERES>`), and parsing its text gives the file's scene.
    #[test]
    fn the_standard_scenes_load() {
        for name in SCENES {
            let file = load(name);
            let parsed: SceneFile<MAX_SPHERES> = scene_file::parse(text(name).unwrap()).unwrap();
            assert_eq!(parsed.scene.spheres(), file.scene.spheres(), "{name}");
        }
        for name in FEATURE_SCENES {
            let file = load_full(name);
            assert!(file.has_features(), "{name}");
        }
    }
}
