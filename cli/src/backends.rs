//! Backend selection for `--backend`: reference, cpu, gpu or auto.

use prismatic_core::{Backend, BackendError, ReferenceBackend};
use prismatic_cpu::CpuBackend;
#[cfg(feature = "gpu")]
use prismatic_gpu::{AdapterChoice, GpuBackend};

/// What the user asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum BackendChoice {
    /// The scalar reference in prismatic-core (single thread).
    Reference,
    /// The packet-SIMD CPU backend.
    Cpu,
    /// The wgpu compute backend (any adapter, a software one included).
    Gpu,
    /// The fastest backend this machine has: a hardware GPU, else the CPU.
    Auto,
}

/// A backend ready to use, with a note on how it was chosen.
pub struct Selected {
    /// The backend.
    pub backend: Box<dyn Backend>,
    /// Which device it runs on, or why it was picked.
    pub note: Option<String>,
}

/// Creates the backend for `choice`.
pub fn select(choice: BackendChoice) -> Result<Selected, BackendError> {
    match choice {
        BackendChoice::Reference => Ok(Selected { backend: Box::new(ReferenceBackend), note: None }),
        BackendChoice::Cpu => Ok(Selected { backend: Box::new(CpuBackend::new()), note: None }),
        BackendChoice::Gpu | BackendChoice::Auto => select_gpu(choice),
    }
}

/// The GPU backend for `--backend gpu`, or for `auto` on a hardware GPU
/// (else the CPU backend).
#[cfg(feature = "gpu")]
fn select_gpu(choice: BackendChoice) -> Result<Selected, BackendError> {
    match choice {
        BackendChoice::Gpu => {
            let gpu = GpuBackend::new(AdapterChoice::Any)?;
            let note = gpu.adapter().map(|a| format!("gpu backend on {}", prismatic_gpu::describe(a)));
            Ok(Selected { backend: Box::new(gpu), note })
        }
        BackendChoice::Auto => match GpuBackend::new(AdapterChoice::HardwareOnly) {
            Ok(gpu) => {
                let on = gpu.adapter().map_or_else(|| "a GPU".to_string(), prismatic_gpu::describe);
                Ok(Selected { backend: Box::new(gpu), note: Some(format!("auto picked the gpu backend on {on}")) })
            }
            Err(why) => Ok(Selected {
                backend: Box::new(CpuBackend::new()),
                note: Some(format!("auto picked the cpu backend ({} threads; {why})", rayon_threads())),
            }),
        },
        _ => unreachable!("only gpu and auto choose a GPU"),
    }
}

/// Built without the `gpu` feature: `--backend gpu` is an error, `auto` the CPU backend.
#[cfg(not(feature = "gpu"))]
fn select_gpu(choice: BackendChoice) -> Result<Selected, BackendError> {
    match choice {
        BackendChoice::Gpu => Err(BackendError::NoDevice {
            what: "GPU backend",
            detail: "this prismatic was built without the `gpu` feature".into(),
        }),
        _ => Ok(Selected {
            backend: Box::new(CpuBackend::new()),
            note: Some(format!(
                "auto picked the cpu backend ({} threads; built without the gpu feature)",
                rayon_threads()
            )),
        }),
    }
}

/// Threads the CPU backend will use.
fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}
