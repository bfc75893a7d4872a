//! What the display shows ([`Shown`]), compared with the next frame's inputs bit for bit
//! (the rule's steps 1 and 2).

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use crate::camera::CameraParams;
use crate::math::vec3::Vec3;
use crate::method::Method;
use crate::render::Render;
use crate::sampling::Sampling;
use crate::scene::light::Light;
use crate::scene::material::Material;
use crate::scene::plane::Plane;
use crate::scene::sphere::Sphere;
use crate::scene::{Scene, Settings};
use crate::trace::options::{Options, SecondaryOrigin};

use super::plan_integer::IntRule;

/// What the display shows: the inputs of the last frame drawn, never its pixels.
#[derive(Clone, Debug)]
pub(super) struct Shown<const N: usize, const L: usize, const P: usize, const D: usize> {
    pub(super) scene: Scene<N, L, P, D>,
    pub(super) params: CameraParams,
    pub(super) method: Method,
    pub(super) sampling: Sampling,
    pub(super) options: Options,
    pub(super) offset: Point,
    /// The target's bounding box (for bands: the image).
    pub(super) target: Rectangle,
    /// The integer kernel's rule for this frame, as its plan found it.
    pub(super) int_rule: IntRule,
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> Shown<N, L, P, D> {
    /// Whether `render`, drawn onto `target` (its bounding box) at `offset`, keeps this
    /// frame's frame-wide state (rule step 1) as far as the inputs say.
    ///
    /// The inputs are the camera, the method, sampling, options, offset and target, and
    /// the scene's frame-wide numbers. What the method derives from them (the frame's
    /// scale, the integer kernel's quantisation) each rule compares itself.
    pub(super) fn same_frame<C>(
        &self,
        render: &Render<'_, N, C, L, P, D>,
        target: Rectangle,
        offset: Point,
    ) -> bool {
        same_params(&self.params, render.camera().params())
            && self.method == render.method()
            && self.sampling == render.sampling()
            && same_options(render.options(), self.options)
            && self.offset == offset
            && self.target == target
            && same_frame_wide(&self.scene, render.scene())
    }

    /// Whether sphere `k` of `scene` differs from this frame's bit for bit (rule step
    /// 2); a sphere only one of them has differs.
    pub(super) fn changed(&self, scene: &Scene<N, L, P, D>, k: usize) -> bool {
        match (self.scene.spheres().get(k), scene.spheres().get(k)) {
            (Some(a), Some(b)) => !same_sphere(a, b),
            _ => true,
        }
    }
}

// Scenes are compared by their bits: `-0.0` and `0.0` differ, and a NaN equals itself,
// so a change is never missed and an unchanged object never redrawn.

fn bits(v: Vec3) -> [u32; 3] {
    [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()]
}

fn same_material(a: &Material, b: &Material) -> bool {
    [a.specular, a.shininess, a.reflect].map(f32::to_bits)
        == [b.specular, b.shininess, b.reflect].map(f32::to_bits)
}

fn same_sphere(a: &Sphere, b: &Sphere) -> bool {
    bits(a.center) == bits(b.center)
        && a.radius.to_bits() == b.radius.to_bits()
        && a.color == b.color
        && same_material(&a.material, &b.material)
}

fn same_light(a: &Light, b: &Light) -> bool {
    match (*a, *b) {
        (
            Light::Directional {
                direction: d,
                intensity: i,
            },
            Light::Directional {
                direction: e,
                intensity: j,
            },
        )
        | (
            Light::Point {
                position: d,
                intensity: i,
            },
            Light::Point {
                position: e,
                intensity: j,
            },
        ) => bits(d) == bits(e) && i.to_bits() == j.to_bits(),
        _ => false,
    }
}

fn same_plane(a: &Plane, b: &Plane) -> bool {
    bits(a.point) == bits(b.point)
        && bits(a.normal) == bits(b.normal)
        && a.color == b.color
        && a.checker == b.checker
        && a.checker_size.to_bits() == b.checker_size.to_bits()
        && same_material(&a.material, &b.material)
}

fn same_settings(a: Settings, b: Settings) -> bool {
    a.ambient.to_bits() == b.ambient.to_bits() && a.max_depth == b.max_depth && a.shadows == b.shadows
}

fn same_options(a: Options, b: Options) -> bool {
    let eps = |o: Options| match o.secondary {
        SecondaryOrigin::Convex => None,
        SecondaryOrigin::Epsilon(e) => Some(e.to_bits()),
    };
    eps(a) == eps(b)
        && a.span_culling == b.span_culling
        && a.anchor_interval == b.anchor_interval
        && a.shadow_any_hit == b.shadow_any_hit
}

fn same_params(a: &CameraParams, b: &CameraParams) -> bool {
    bits(a.eye) == bits(b.eye)
        && bits(a.look_at) == bits(b.look_at)
        && bits(a.up) == bits(b.up)
        && a.fov_y.to_bits() == b.fov_y.to_bits()
        && a.fov_x.map(f32::to_bits) == b.fov_x.map(f32::to_bits)
        && a.size == b.size
}

/// Everything of the scene but its spheres' own numbers: the background, settings,
/// lights, planes and the number of spheres.
fn same_frame_wide<const N: usize, const L: usize, const P: usize, const D: usize>(
    a: &Scene<N, L, P, D>,
    b: &Scene<N, L, P, D>,
) -> bool {
    a.background() == b.background()
        && same_settings(a.settings(), b.settings())
        && a.spheres().len() == b.spheres().len()
        && a.lights().len() == b.lights().len()
        && a.planes().len() == b.planes().len()
        && a.lights().iter().zip(b.lights()).all(|(x, y)| same_light(x, y))
        && a.planes().iter().zip(b.planes()).all(|(x, y)| same_plane(x, y))
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::pixelcolor::Rgb888;

    fn ball(x: f32) -> Sphere {
        Sphere::new(Vec3::new(x, 0.0, 0.0), 1.0, Rgb888::new(255, 0, 0))
    }

    fn shown(scene: Scene<2>) -> Shown<2, 0, 0, 0> {
        Shown {
            scene,
            params: CameraParams::new(
                Vec3::new(0.0, 0.0, 5.0),
                Vec3::ZERO,
                Vec3::new(0.0, 1.0, 0.0),
                1.0,
                Size::new(8, 8),
            ),
            method: Method::F32,
            sampling: Sampling::Center,
            options: Options::default(),
            offset: Point::zero(),
            target: Rectangle::new(Point::zero(), Size::new(8, 8)),
            int_rule: IntRule::Unknown,
        }
    }

    #[test]
    fn spheres_compare_by_their_bits() {
        assert!(same_sphere(&ball(1.0), &ball(1.0)));
        // `-0.0` and `0.0` are equal numbers but different bits: a change.
        assert!(!same_sphere(&ball(-0.0), &ball(0.0)));
        // A NaN equals itself: an unchanged object is never redrawn.
        let nan = ball(f32::NAN);
        assert!(same_sphere(&nan, &nan));
        let shiny = Sphere {
            material: Material::new(0.5, 8.0, 0.0),
            ..ball(1.0)
        };
        assert!(!same_sphere(&shiny, &ball(1.0)));
    }

    #[test]
    fn lights_of_another_kind_differ() {
        let v = Vec3::new(0.0, -1.0, 0.0);
        assert!(same_light(
            &Light::directional(v, 1.0),
            &Light::directional(v, 1.0)
        ));
        assert!(!same_light(&Light::directional(v, 1.0), &Light::point(v, 1.0)));
        assert!(!same_light(&Light::point(v, 1.0), &Light::point(v, 0.5)));
    }

    #[test]
    fn options_compare_the_secondary_origin() {
        let convex = Options::default().with_secondary(SecondaryOrigin::Convex);
        assert!(same_options(convex, convex));
        assert!(!same_options(
            convex,
            convex.with_secondary(SecondaryOrigin::Epsilon(1e-3))
        ));
    }

    #[test]
    fn a_sphere_only_one_frame_has_changed() {
        let mut scene: Scene<2> = Scene::from_array([ball(0.0)], Rgb888::BLACK);
        let old = shown(scene.clone());
        assert!(!old.changed(&scene, 0));
        scene.set_sphere(0, ball(0.5)).unwrap();
        assert!(old.changed(&scene, 0));
        scene.push(ball(3.0)).unwrap();
        assert!(old.changed(&scene, 1));
        // Another number of spheres is a frame-wide change.
        assert!(!same_frame_wide(&old.scene, &scene));
    }
}
