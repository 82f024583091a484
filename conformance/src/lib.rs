//! prismatic-conformance: what a backend of prismatic's render protocol
//! must do, as test bodies a backend crate runs against itself.
//!
//! A backend author implements `prismatic_core::Backend` and
//! `prismatic_core::Render` and adds one test file:
//!
//! ```ignore
//! // tests/conformance.rs of a backend crate
//! prismatic_conformance::conformance_tests!(Some(MyBackend::new()));
//! ```
//!
//! which makes one `#[test]` per body of [`suite`]: photon maps and images
//! against the scalar reference (gathered, light traced, with sampled view
//! paths, a caustic layer in an engine's frame), partial renders that merge exactly, passes
//! in any order, updates that give a fresh render, read-outs and
//! statistics. The expression may give `None` (a GPU backend on a machine
//! without an adapter): the tests then say so and pass, except under
//! `CI=true`, where a missing backend fails.
//!
//! The crate also holds the comparison rules of every parity test
//! ([`tolerance`], [`compare`]) and the generated cases of the kernel twin
//! tests ([`twins`]), which compare a backend's copies of the core's optics
//! and estimator functions with the originals.

pub mod compare;
pub mod scenes;
pub mod suite;
pub mod tolerance;
pub mod twins;

/// Makes one `#[test]` per body of the suite, each running it on the
/// backend `$backend` gives (an `Option`: `None` skips, outside CI).
#[macro_export]
macro_rules! conformance_tests {
    ($backend:expr) => {
        $crate::conformance_tests!(@tests $backend;
            photon_maps_match_the_reference,
            images_match_the_reference,
            light_traced_images_match_the_reference,
            sampled_view_paths_match_the_reference,
            caustic_layers_match_the_reference,
            partial_renders_merge_into_one_run,
            passes_run_in_any_order_and_once,
            updates_give_a_fresh_renders_sums,
            read_outs_and_statistics,
            a_scene_without_caustics_is_its_base
        );
    };
    (@tests $backend:expr; $($case:ident),*) => {
        $(
            #[test]
            fn $case() {
                match $backend {
                    Some(mut backend) => $crate::suite::$case(&mut backend),
                    None if std::env::var_os("CI").is_some() => panic!("CI=true and the backend is missing"),
                    None => eprintln!("SKIPPING {}: the backend is missing on this machine", stringify!($case)),
                }
            }
        )*
    };
}
