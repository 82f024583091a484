//! A session's lights that change each pass (an environment's drawn suns,
//! `prismatic_core::plan::drawn_suns`; area lights' shadow aims,
//! `prismatic_core::plan::area_aims`; a choice of emissive triangles,
//! `prismatic_core::plan::drawn_triangles`): before a pass's view rays and
//! photons, the scene buffers get that pass's lights, written in place
//! (each light's record, a sun's projection map), unless they hold them
//! already.

use super::GpuSession;
use crate::scene::EncodedScene;
use prismatic_core::BackendError;

impl GpuSession {
    /// Makes the scene buffers hold the lights of pass `pass` (a no-op for
    /// a scene whose lights stay fixed).
    pub(super) fn use_lights_of(&mut self, pass: u32) -> Result<(), BackendError> {
        if self.lights_pass == pass {
            return Ok(());
        }
        let Some(scene) = self.scene.lights_of_pass(pass) else { return Ok(()) };
        match self.encoded.point_lights(&scene) {
            Some(changed) => self.ctx.checked("pointing the pass's lights", || {
                self.buffers.write_lights(&self.ctx, &self.encoded, &changed);
            })?,
            None => {
                // A projection map changed its size, or other emissive triangles
                // were chosen: the scene again, its changed bytes written.
                let encoded = EncodedScene::new(&scene);
                let regrouped = self.ctx.checked("pointing the pass's lights", || {
                    self.buffers.update(&self.ctx, &self.pipelines.scene_layout, &self.encoded, &encoded)
                })?;
                self.encoded = encoded;
                if regrouped {
                    self.bind_points()?;
                }
            }
        }
        self.lights_pass = pass;
        Ok(())
    }
}
