//! The pinhole camera: a right-handed look-at view and OpenGL's perspective
//! projection (NDC z in [-1, 1]).

use glam::{Mat4, Vec3};

use crate::limits::{MAX_EYE_DISTANCE, MIN_EYE_DISTANCE};
use crate::text::format_number;

/// Why a camera cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CameraError {
    /// A value is NaN or infinite.
    #[error("camera.{0} is not a finite number")]
    NonFinite(&'static str),
    /// The eye and the target coincide.
    #[error("camera.eye equals camera.target: the view direction is undefined")]
    EyeAtTarget,
    /// The eye and the target are apart, but by so little that the view
    /// direction cannot be computed in `f32` (its squared length vanishes).
    #[error(
        "camera.eye and camera.target are {} apart: too close to define a view direction \
         (at least {} apart)",
        format_number(*.distance),
        format_number(MIN_EYE_DISTANCE)
    )]
    EyeTooClose {
        /// How far apart they are.
        distance: f32,
    },
    /// The eye is so far from the target that the view direction's squared
    /// length overflows `f32`.
    #[error(
        "camera.eye and camera.target are {} apart: too far to define a view direction \
         (at most {} apart)",
        format_number(*.distance),
        format_number(MAX_EYE_DISTANCE)
    )]
    EyeTooFar {
        /// How far apart they are.
        distance: f32,
    },
    /// `up` is zero or parallel to the view direction.
    #[error("camera.up is zero or parallel to the view direction")]
    BadUp,
    /// The field of view is outside (0, 180) degrees.
    #[error(
        "camera.fov_y must be strictly between 0 and 180 degrees, got {}",
        format_number(*.0)
    )]
    FieldOfView(f32),
    /// The clipping planes are not 0 < near < far.
    #[error(
        "camera.near and camera.far must satisfy 0 < near < far, got near = {}, far = {}",
        format_number(*.near),
        format_number(*.far)
    )]
    DepthRange {
        /// Near plane distance.
        near: f32,
        /// Far plane distance.
        far: f32,
    },
}

/// Where the viewer stands and what it sees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// The viewer's position.
    pub eye: Vec3,
    /// The point looked at.
    pub target: Vec3,
    /// Which way is up on the screen.
    pub up: Vec3,
    /// Vertical field of view, in degrees.
    pub fov_y_degrees: f32,
    /// Distance to the near clipping plane.
    pub near: f32,
    /// Distance to the far clipping plane.
    pub far: f32,
}

impl Camera {
    /// A camera that frames a sphere of `radius` around `centre` from the +z
    /// side, for an image of the given aspect ratio (width / height).
    pub fn framing_sphere(centre: Vec3, radius: f32, fov_y_degrees: f32, aspect: f32) -> Camera {
        let half_y = (fov_y_degrees.to_radians() * 0.5).clamp(1e-3, 1.5);
        let half_x = (half_y.tan() * aspect).atan();
        let radius = if radius > 0.0 { radius } else { 1.0 };
        let distance = 1.05 * radius / half_y.min(half_x).sin();
        Camera {
            eye: centre + Vec3::Z * distance,
            target: centre,
            up: Vec3::Y,
            fov_y_degrees,
            near: (distance - 2.0 * radius).max(0.01 * distance),
            far: distance + 2.0 * radius,
        }
    }

    /// The camera moved around its target: `yaw` degrees about `up`, then
    /// `pitch` degrees towards `up` (clamped short of the pole).
    pub fn orbit(&self, yaw_degrees: f32, pitch_degrees: f32) -> Camera {
        let offset = self.eye - self.target;
        let distance = offset.length();
        let up = self.up.normalize_or_zero();
        if distance == 0.0 || up == Vec3::ZERO {
            return *self;
        }
        let yawed = glam::Quat::from_axis_angle(up, yaw_degrees.to_radians()) * offset;
        let dir = yawed / distance;
        let elevation = dir.dot(up).clamp(-1.0, 1.0).asin();
        let limit = 89.0f32.to_radians();
        let new_elevation = (elevation + pitch_degrees.to_radians()).clamp(-limit, limit);
        let horizontal = (dir - up * dir.dot(up)).normalize_or_zero();
        let horizontal = if horizontal == Vec3::ZERO {
            up.any_orthonormal_vector()
        } else {
            horizontal
        };
        let new_dir = horizontal * new_elevation.cos() + up * new_elevation.sin();
        Camera {
            eye: self.target + new_dir * distance,
            ..*self
        }
    }

    /// Checks that the camera defines a view and a projection.
    ///
    /// # Errors
    /// [`CameraError`] naming the field at fault.
    pub fn validate(&self) -> Result<(), CameraError> {
        for (name, ok) in [
            ("eye", self.eye.is_finite()),
            ("target", self.target.is_finite()),
            ("up", self.up.is_finite()),
            ("fov_y", self.fov_y_degrees.is_finite()),
            ("near", self.near.is_finite()),
            ("far", self.far.is_finite()),
        ] {
            if !ok {
                return Err(CameraError::NonFinite(name));
            }
        }
        let forward = self.target - self.eye;
        if forward == Vec3::ZERO {
            return Err(CameraError::EyeAtTarget);
        }
        if !forward.length_squared().is_normal() {
            // Too close (or so far that the square overflows): say how far
            // apart they are, computed without overflow or underflow.
            let largest = forward.abs().max_element();
            let distance = largest * (forward / largest).length();
            return Err(if distance < 1.0 {
                CameraError::EyeTooClose { distance }
            } else {
                CameraError::EyeTooFar { distance }
            });
        }
        if forward.normalize().cross(self.up).length_squared() < 1e-12 {
            return Err(CameraError::BadUp);
        }
        if !(self.fov_y_degrees > 0.0 && self.fov_y_degrees < 180.0) {
            return Err(CameraError::FieldOfView(self.fov_y_degrees));
        }
        if !(self.near > 0.0 && self.near < self.far) {
            return Err(CameraError::DepthRange {
                near: self.near,
                far: self.far,
            });
        }
        Ok(())
    }

    /// World to eye space: right-handed, the camera looking down −z.
    pub fn view(&self) -> Mat4 {
        Mat4::look_at_rh(self.eye, self.target, self.up)
    }

    /// Eye space to clip space, as OpenGL's `gluPerspective`.
    pub fn projection(&self, aspect: f32) -> Mat4 {
        Mat4::perspective_rh_gl(self.fov_y_degrees.to_radians(), aspect, self.near, self.far)
    }
}
