//! The pinhole camera: primary rays through pixel centres (or any point of
//! a pixel), and the projection of a point back into the pixel that sees it.

use crate::geometry::primitive::Ray;
use crate::model::scene::Camera;
use crate::util::math::{radians, tan};
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
    /// The optical axis: the direction through the image centre, of unit
    /// length (the image plane lies at distance 1).
    pub forward: Vec3,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

/// Where the camera sees a point: its pixel and its depth along the
/// optical axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    /// Pixel column.
    pub x: u32,
    /// Pixel row (down).
    pub y: u32,
    /// Distance of the point from the eye along the optical axis.
    pub depth: f32,
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
            forward,
            width,
            height,
        }
    }

    /// The pixel whose square the ray from the eye to `p` crosses, and
    /// `p`'s depth; `None` when `p` is behind the eye or outside the image.
    /// The inverse of [`PinholeCamera::ray`] (which aims at the square's centre).
    #[inline]
    pub fn project(&self, p: Vec3) -> Option<Projection> {
        let v = p - self.origin;
        let depth = v.dot(self.forward);
        // Behind the eye, or NaN (a point at the eye itself).
        if depth.is_nan() || depth <= 0.0 {
            return None;
        }
        // The point where the ray meets the image plane, from the corner.
        let q = v / depth - self.corner;
        let u = q.dot(self.right) / self.right.length_squared();
        let w = q.dot(self.down) / self.down.length_squared();
        let inside = |c: f32, n: u32| c >= 0.0 && c < n as f32;
        (inside(u, self.width) && inside(w, self.height)).then(|| Projection {
            x: (u as u32).min(self.width - 1),
            y: (w as u32).min(self.height - 1),
            depth,
        })
    }

    /// The area of one pixel on the image plane (at distance 1 from the eye).
    #[inline]
    pub fn pixel_area(&self) -> f32 {
        self.right.length() * self.down.length()
    }

    /// The primary ray through the centre of pixel (x, y), y down.
    #[inline]
    pub fn ray(&self, x: u32, y: u32) -> Ray {
        self.ray_through(x, y, (0.5, 0.5))
    }

    /// The primary ray through the point of pixel (x, y) at fractions
    /// `(fx, fy)` of its width and height from its top-left corner.
    #[inline]
    pub fn ray_through(&self, x: u32, y: u32, (fx, fy): (f32, f32)) -> Ray {
        let d = self.corner + self.right * (x as f32 + fx) + self.down * (y as f32 + fy);
        Ray::new(self.origin, d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_on_a_pixels_ray_projects_into_that_pixel() {
        let cam = Camera { position: Vec3::new(0.3, 1.0, 4.0), look_at: Vec3::ZERO, up: Vec3::Y, fov_deg: 35.0 };
        let camera = PinholeCamera::new(&cam, 64, 48);
        for (x, y) in [(0, 0), (63, 0), (0, 47), (63, 47), (20, 31)] {
            let ray = camera.ray(x, y);
            let p = ray.at(3.7);
            let seen = camera.project(p).expect("in view");
            assert_eq!((seen.x, seen.y), (x, y));
            assert!((seen.depth - 3.7 * ray.direction.dot(camera.forward)).abs() < 1e-5);
        }
        assert_eq!(camera.project(cam.position + (cam.position - cam.look_at)), None, "behind the eye");
        assert_eq!(camera.project(camera.ray(0, 0).at(2.0) - camera.right * 2.0), None, "left of the image");
        // 64 × 48 pixels tile the image plane: 2 tan(17.5°) high, 4/3 of that wide.
        let h = 2.0 * (17.5f32).to_radians().tan();
        assert!((camera.pixel_area() * 64.0 * 48.0 - h * h * 4.0 / 3.0).abs() < 1e-5);
    }
}
