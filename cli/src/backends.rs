//! Backend selection for `--backend`: reference, cpu, gpu or auto.

use prismatic_core::{Backend, BackendError, ReferenceBackend};
use prismatic_cpu::CpuBackend;

/// What the user asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum BackendChoice {
    /// The scalar reference in prismatic-core (single thread).
    Reference,
    /// The packet-SIMD CPU backend.
    Cpu,
    /// The wgpu compute backend.
    Gpu,
    /// The fastest backend this machine has.
    Auto,
}

/// A backend ready to use, with a note on how it was chosen (for `auto`).
pub struct Selected {
    /// The backend.
    pub backend: Box<dyn Backend>,
    /// Why it was picked, when the user did not pick it.
    pub note: Option<String>,
}

/// Creates the backend for `choice`.
pub fn select(choice: BackendChoice) -> Result<Selected, BackendError> {
    match choice {
        BackendChoice::Reference => Ok(Selected { backend: Box::new(ReferenceBackend), note: None }),
        BackendChoice::Cpu => Ok(Selected { backend: Box::new(CpuBackend::new()), note: None }),
        BackendChoice::Gpu => Err(BackendError::NotBuilt { backend: "gpu", hint: "--backend cpu" }),
        BackendChoice::Auto => Ok(Selected {
            backend: Box::new(CpuBackend::new()),
            note: Some(format!(
                "auto picked the cpu backend ({} threads; the gpu backend is not built yet)",
                rayon_threads()
            )),
        }),
    }
}

/// Threads the CPU backend will use.
fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}
