//! A session's grid levels, twin of the levels of
//! `prismatic_core::render::reference::gather_pass`: the photons bucketed at the
//! pass radius (level 0, always built) and, when first radii fall there,
//! at a quarter and a sixteenth of it, so that a point in a dense caustic
//! scans cells of its own size rather than the pass radius's. The pilot's
//! `first_radius` marks on the device which levels the points need; the
//! mark is read back without waiting on a hardware GPU (a software device,
//! which gathers in segments, waits for it), and until it comes (or for a
//! point whose level is not built) the next coarser grid serves: the
//! gather finds the same photons in any grid whose cells are at least its
//! diameter.

use crate::context::GpuContext;
use crate::grid::DeviceGrid;
use crate::pipelines::Pipelines;
use crate::readback::PendingRead;
use crate::scene::SceneBuffers;
use crate::trace::PhotonPass;
use prismatic_core::BackendError;
use prismatic_core::plan::schedule::{GRID_LEVELS, level_radius};

/// The built grid levels and the mark of the levels the points need.
pub struct GridLevels {
    /// Level l's grid, when built; level 0's always is.
    grids: [Option<DeviceGrid>; GRID_LEVELS],
    /// One u32 on the device: bit l set when some point's first radius
    /// falls in level l (written by `first_radius`).
    pub used: wgpu::Buffer,
    /// The mark on its way back.
    pending: Option<PendingRead>,
}

impl GridLevels {
    /// Level 0's grid over `photons`' map.
    pub fn new(
        ctx: &GpuContext,
        pipelines: &Pipelines,
        buffers: &SceneBuffers,
        photons: &PhotonPass,
    ) -> Result<Self, BackendError> {
        let used = ctx.checked("allocating the grid levels", || {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("prismatic grid levels used"),
                size: 16,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        })?;
        let mut grids: [Option<DeviceGrid>; GRID_LEVELS] = Default::default();
        grids[0] = Some(grid(ctx, pipelines, buffers, photons)?);
        Ok(GridLevels { grids, used, pending: None })
    }

    /// Bit l set when level l is built.
    pub fn built(&self) -> u32 {
        self.grids.iter().enumerate().filter(|(_, g)| g.is_some()).map(|(l, _)| 1 << l).sum()
    }

    /// The built levels and their grids, coarsest first.
    pub fn iter(&self) -> impl Iterator<Item = (usize, &DeviceGrid)> {
        self.grids.iter().enumerate().filter_map(|(l, g)| g.as_ref().map(|g| (l, g)))
    }

    /// The built levels' grids allocated again for a new photon pass.
    pub fn reallocate(
        &mut self,
        ctx: &GpuContext,
        pipelines: &Pipelines,
        buffers: &SceneBuffers,
        photons: &PhotonPass,
    ) -> Result<(), BackendError> {
        for slot in self.grids.iter_mut().filter(|g| g.is_some()) {
            *slot = Some(grid(ctx, pipelines, buffers, photons)?);
        }
        Ok(())
    }

    /// Submits a rebuild of every built level over `photons`' map (the
    /// pass's cursor is the photon count) for a pass of radius `r_pass`.
    pub fn rebuild(
        &self,
        ctx: &GpuContext,
        pipelines: &Pipelines,
        buffers: &mut SceneBuffers,
        photons: &PhotonPass,
        r_pass: f32,
    ) -> Result<(), BackendError> {
        for (level, grid) in self.iter() {
            buffers.params.inv_cell = inv_cell(r_pass, level);
            grid.rebuild(ctx, pipelines, buffers, photons.capacity(), Some(photons.cursor()))?;
        }
        Ok(())
    }

    /// A new pilot pass follows: its first radii mark the levels afresh
    /// (the built ones stay until the new mark comes back).
    pub fn forget(&mut self, ctx: &GpuContext) -> Result<(), BackendError> {
        self.pending = None;
        ctx.checked("clearing the grid levels", || {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            encoder.clear_buffer(&self.used, 0, None);
            ctx.submit(encoder);
        })
    }

    /// Starts reading back the levels the pilot's first radii marked.
    pub fn read_used(&mut self, ctx: &GpuContext) -> Result<(), BackendError> {
        self.pending = Some(PendingRead::start(ctx, &self.used, "the grid levels used")?);
        Ok(())
    }

    /// Waits until the mark on its way back (if any) has come.
    pub fn wait_for_mark(&self, ctx: &GpuContext) -> Result<(), BackendError> {
        self.pending.as_ref().map_or(Ok(()), |pending| pending.wait(ctx))
    }

    /// Whether the mark is on its way back.
    pub fn reading(&self) -> bool {
        self.pending.is_some()
    }

    /// When the mark has come back (the caller polled the device), builds
    /// the levels it names and drops the others; true when the built set
    /// changed (the gathers' bindings must be made again). The new grids
    /// are filled by the next [`GridLevels::rebuild`].
    pub fn adopt(
        &mut self,
        ctx: &GpuContext,
        pipelines: &Pipelines,
        buffers: &SceneBuffers,
        photons: &PhotonPass,
    ) -> Result<bool, BackendError> {
        let Some(pending) = &self.pending else { return Ok(false) };
        let Some(used) = pending.value()? else { return Ok(false) };
        self.pending = None;
        let wanted = used | 1;
        if wanted == self.built() {
            return Ok(false);
        }
        for (level, slot) in self.grids.iter_mut().enumerate() {
            match (wanted & (1 << level) != 0, slot.is_some()) {
                (true, false) => *slot = Some(grid(ctx, pipelines, buffers, photons)?),
                (false, true) => *slot = None,
                _ => {}
            }
        }
        Ok(true)
    }
}

/// `1 / cell size` of grid level `level` in a pass of radius `r_pass`
/// (cells one level-radius disc across).
pub fn inv_cell(r_pass: f32, level: usize) -> f32 {
    1.0 / (2.0 * level_radius(r_pass, level))
}

/// A grid's buffers for every photon `photons` can store.
fn grid(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    buffers: &SceneBuffers,
    photons: &PhotonPass,
) -> Result<DeviceGrid, BackendError> {
    DeviceGrid::new(ctx, pipelines, buffers, &photons.photons, photons.capacity())
}
