//! A session's environment suns drawn each pass (`prismatic_core::plan::drawn_suns`):
//! before a pass's view rays and photons, the scene buffers get that
//! pass's suns, written in place (each sun's record and its projection
//! map), unless they hold them already.

use super::GpuSession;
use crate::scene::EncodedScene;
use prismatic_core::BackendError;

impl GpuSession {
    /// Makes the scene buffers hold the suns of pass `pass` (a no-op for a
    /// scene whose suns stay fixed).
    pub(super) fn use_suns_of(&mut self, pass: u32) -> Result<(), BackendError> {
        if self.suns_pass == pass {
            return Ok(());
        }
        let Some(scene) = self.scene.suns_of_pass(pass) else { return Ok(()) };
        match self.encoded.point_suns(&scene) {
            Some(changed) => self.ctx.checked("pointing the environment's suns", || {
                self.buffers.write_suns(&self.ctx, &self.encoded, &changed);
            })?,
            None => {
                // A projection map changed its size: the scene again, its changed bytes written.
                let encoded = EncodedScene::new(&scene);
                let regrouped = self.ctx.checked("pointing the environment's suns", || {
                    self.buffers.update(&self.ctx, &self.pipelines.scene_layout, &self.encoded, &encoded)
                })?;
                self.encoded = encoded;
                if regrouped {
                    self.bind_points()?;
                }
            }
        }
        self.suns_pass = pass;
        Ok(())
    }
}
