//! The pinhole camera: primary rays through pixel centres.

use crate::geometry::Ray;
use crate::math::{radians, tan};
use crate::scene::Camera;
use glam::Vec3;

/// A camera with its frame precomputed for an image size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PinholeCamera {
    /// Eye point.
    pub origin: Vec3,
    /// Image-plane step per pixel to the right.
    pub right: Vec3,
    /// Image-plane step per pixel downward.
    pub down: Vec3,
    /// Direction through the top-left corner of the image.
    pub corner: Vec3,
}

impl PinholeCamera {
    /// Sets the camera up for a `width` × `height` image.
    pub fn new(cam: &Camera, width: u32, height: u32) -> Self {
        let forward = (cam.look_at - cam.position).normalize();
        let right = forward.cross(cam.up).normalize();
        let up = right.cross(forward);
        let half_h = tan(radians(cam.fov_deg) * 0.5);
        let half_w = half_h * width as f32 / height as f32;
        let px = 2.0 * half_w / width as f32;
        let py = 2.0 * half_h / height as f32;
        PinholeCamera {
            origin: cam.position,
            right: right * px,
            down: -up * py,
            corner: forward - right * half_w + up * half_h,
        }
    }

    /// The primary ray through the centre of pixel (x, y), y down.
    #[inline]
    pub fn ray(&self, x: u32, y: u32) -> Ray {
        let d = self.corner + self.right * (x as f32 + 0.5) + self.down * (y as f32 + 0.5);
        Ray::new(self.origin, d)
    }
}
