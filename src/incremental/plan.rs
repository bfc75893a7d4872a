//! The rule for an `f32` frame (module docs, steps 1 to 4): the regions of the image
//! that can differ from the frame the display shows.

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

use crate::camera::cone::ViewCone;
use crate::camera::span::{Margin, Silhouette};
use heapless::VecView;

use crate::camera::Camera;
use crate::error::FrameError;
use crate::integer::IntSphere;
use crate::math::SqrtFn;
use crate::method::dispatch::{dispatch, Visit};
use crate::method::intersect::{Scale, SphereGeom, TestStrategy};
use crate::method::stepping::Stepper;
use crate::method::{Arithmetic, SphereTest};
use crate::render::Render;
use crate::sampling::{shares_samples, small_box, Sampling};
use crate::scene::sphere::Sphere;
use crate::scene::Scene;
use crate::trace::lit::shadow::shadow_regions;
use crate::trace::lit::smallest_radius;
use crate::trace::lit::ties::same_ties;
use crate::trace::options::Options;

use super::can_shadow::can_shadow;
use super::plan_integer::IntRule;
use super::{Changes, Incremental, STRIP_SETUP};

/// Whether the render asks for the integer kernel on a frame it can draw (spheres only,
/// one ray a pixel): where its rule decides.
// Inlined: with a constant method this is a constant.
#[inline(always)]
pub(super) fn integer_kind<const N: usize, C, const L: usize, const P: usize, const D: usize>(
    render: &Render<'_, N, C, L, P, D>,
) -> bool {
    render.method().arithmetic == Arithmetic::Integer
        && !Scene::<N, L, P, D>::FEATURES
        && render.sampling() == Sampling::Center
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> Incremental<N, L, P, D> {
    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    pub(super) fn plan<C>(
        &self,
        render: &Render<'_, N, C, L, P, D>,
        target: Rectangle,
        picture: Option<&mut VecView<IntSphere>>,
    ) -> Changes {
        self.plan_at(render, target, render.offset(), picture)
    }

    /// The rule (module docs), once per frame; with `picture`, the integer kernel's
    /// picture of the frame where its rule takes it, for the draw.
    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    pub(super) fn plan_at<C>(
        &self,
        render: &Render<'_, N, C, L, P, D>,
        target: Rectangle,
        offset: Point,
        picture: Option<&mut VecView<IntSphere>>,
    ) -> Changes {
        let mut rule = IntRule::Unknown;
        if integer_kind(render) {
            if let Some(plan) = self.plan_integer(render, target, offset, picture) {
                return plan;
            }
            rule = IntRule::Refused;
        }
        // Set in place: the plan is about 1 KB, and a by-value setter copied it on the
        // stack.
        let mut plan = self.plan_f32(render, target, offset);
        plan.int_rule = rule;
        plan
    }

    /// The rule for a frame the `f32` method draws.
    // Inlined, as `Render::draw` is: with a constant method only its code is linked.
    #[inline(always)]
    fn plan_f32<C>(&self, render: &Render<'_, N, C, L, P, D>, target: Rectangle, offset: Point) -> Changes {
        let camera = render.camera();
        let size = camera.size();
        let scene = render.scene();
        let features = Scene::<N, L, P, D>::FEATURES;
        let new = dispatch(
            render.method(),
            Probe {
                scene,
                camera,
                sampling: render.sampling(),
                options: render.options(),
            },
        );
        let Probed {
            scale,
            culled,
            margin,
            step_err,
            shares,
        } = match new {
            Ok(p) => p,
            Err(why) => return Changes::refusal(size, why),
        };
        let full = || Changes::full(size);
        let shown = match &self.shown {
            Some(shown) if shown.same_frame(render, target, offset) => shown,
            _ => return full(),
        };
        let old = dispatch(
            render.method(),
            Probe {
                scene: &shown.scene,
                camera,
                sampling: render.sampling(),
                options: render.options(),
            },
        );
        match old {
            // Every frame-wide decision the render makes from the whole scene is compared:
            // a sphere that moves can change the scale, the cone's culling, or whether
            // adaptive sampling shares samples (which moves edge pixels of spheres that
            // never moved).
            Ok(Probed {
                scale: s,
                culled: c,
                shares: sh,
                ..
            }) if s.0.to_bits() == scale.0.to_bits() && c == culled && sh == shares => {}
            _ => return full(),
        }
        let changed = |k: usize| shown.changed(scene, k);
        let any_changed = (0..scene.spheres().len()).any(changed);
        // The ties and the shadow segments' far limit are frame-wide: a sphere that moves
        // near a lamp, or changes the smallest radius, can change any shadow ray's test.
        if any_changed
            && features
            && (!same_ties(&shown.scene, scene, camera.eye(), scale.0)
                || smallest_radius(shown.scene.spheres()).to_bits()
                    != smallest_radius(scene.spheres()).to_bits())
        {
            return full();
        }
        let pad = match render.sampling() {
            Sampling::Center => 0,
            Sampling::Grid(_) => 1,
            Sampling::Adaptive(_) => 3,
        };
        let shadows = features && L > 0 && scene.settings().shadows;
        let mirrors = features && scene.max_depth() > 0;
        // The shadow regions (`shadow_regions`, `can_shadow`) hold for a shadow test
        // within about 2⁻²² of exact. The lecture notes' algebraic and geometric tests
        // are not (they cancel squares of the shadow ray's length: far from exact from
        // about 100 radii), so their false shadows can fall anywhere a shadow ray is
        // cast: the whole frame.
        let unbounded_shadows = matches!(
            render.method().sphere_test,
            SphereTest::Algebraic | SphereTest::Geometric
        );
        if any_changed
            && ((shadows && (scene.planes().len() > 1 || unbounded_shadows))
                || (mirrors && scene.planes().iter().any(|p| p.material.reflect != 0.0)))
        {
            return full();
        }
        let cone = if culled {
            ViewCone::new(camera, step_err)
        } else {
            None
        };
        let strip_setup = if matches!(render.sampling(), Sampling::Adaptive(_)) {
            STRIP_SETUP.frame_each
        } else {
            STRIP_SETUP.one_frame
        };
        let mut plan = Changes::empty(size, strip_setup, pad);
        let frame = Sil {
            camera,
            scale,
            margin,
            step_err,
            cone: cone.as_ref(),
            span_culling: render.options().span_culling,
        };
        let mut ok = true;
        let add_sphere = |plan: &mut Changes, s: &Sphere| plan.push_silhouette(frame.of(s));
        // Where samples are shared, every pixel whose footprint meets a small
        // silhouette's box is an edge pixel, however far the box reaches beyond the
        // ellipse and its pad: that box too (`small_box`, from the same geometry and
        // culling silhouette as the frame's), for a changed sphere's old and new place.
        let add_box = |plan: &mut Changes, s: &Sphere| {
            let geom = SphereGeom::new(s.center, s.radius, camera.eye(), scale);
            !shares || small_box(&geom, frame.of(s), camera).is_none_or(|b| plan.push_box(b))
        };
        for (k, new_s) in scene.spheres().iter().enumerate() {
            if !changed(k) {
                continue;
            }
            ok &= add_sphere(&mut plan, new_s) && add_box(&mut plan, new_s);
            if let Some(old_s) = shown.scene.spheres().get(k) {
                ok &= add_sphere(&mut plan, old_s) && add_box(&mut plan, old_s);
                if shadows {
                    for s in [old_s, new_s] {
                        shadow_regions(scene, s, camera, (scale, step_err), |sil| {
                            ok &= plan.push_silhouette(sil);
                        });
                    }
                }
            }
        }
        if any_changed {
            // The surfaces a moved sphere's shadow can fall on, and the mirrors that can
            // show it: each unchanged sphere once.
            for (k, s) in scene.spheres().iter().enumerate() {
                let receives = shadows
                    && (0..scene.spheres().len()).filter(|&m| changed(m)).any(|m| {
                        [shown.scene.spheres().get(m), scene.spheres().get(m)]
                            .into_iter()
                            .flatten()
                            .any(|mover| scene.lights().iter().any(|l| can_shadow(mover, s, l)))
                    });
                if !changed(k) && (receives || (mirrors && s.material.reflect != 0.0)) {
                    ok &= add_sphere(&mut plan, s);
                }
            }
        }
        if let Some(stale) = self.stale {
            ok &= plan.push_rect(stale);
        }
        if !ok {
            return full();
        }
        plan.merge();
        plan
    }
}

/// The frame-wide inputs a probe of the method's strategy types reports.
pub(super) struct Probed {
    /// The frame's scale.
    scale: Scale,
    /// Whether the frame left far spheres out.
    culled: bool,
    /// The test's margin, which each silhouette is enlarged by.
    margin: Margin,
    /// The stepping's error bound, which each silhouette is enlarged by.
    step_err: f32,
    /// Whether adaptive sampling shares samples between neighbours: a features frame
    /// always, a Lab #1 frame as [`shares_samples`] decides.
    shares: bool,
}

/// The frame's scale and the silhouettes' margins, as the render decides them.
pub(super) struct Probe<'a, const N: usize, const L: usize, const P: usize, const D: usize> {
    pub(super) scene: &'a Scene<N, L, P, D>,
    pub(super) camera: &'a Camera,
    pub(super) sampling: Sampling,
    pub(super) options: Options,
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> Visit for Probe<'_, N, L, P, D> {
    type Output = Result<Probed, FrameError>;
    fn visit<S: Stepper, T: TestStrategy, Q: SqrtFn>(self) -> Self::Output {
        // Only a Lab #1 frame of one ray a pixel culls for its scale (as `lab1.rs` does).
        let features = Scene::<N, L, P, D>::FEATURES;
        let cull = !features && self.sampling == Sampling::Center;
        let step_err = S::error_bound(self.camera);
        let (scale, culled) =
            crate::trace::frame::frame_scale::<N, L, P, D>(self.scene, self.camera, step_err, cull)?;
        let shares = matches!(self.sampling, Sampling::Adaptive(_))
            && (features
                || shares_samples::<N, L, P, D, S, T, Q>(
                    self.scene,
                    self.camera,
                    self.options,
                    (scale, culled),
                ));
        Ok(Probed {
            scale,
            culled,
            margin: T::MARGIN,
            step_err,
            shares,
        })
    }
}

/// A sphere's silhouette as the frame builds it (`frame.rs`): in the frame's units,
/// with the test's margin and the stepping's error bound; none where the frame's cone
/// left the sphere out.
struct Sil<'a> {
    camera: &'a Camera,
    scale: Scale,
    margin: Margin,
    step_err: f32,
    cone: Option<&'a ViewCone>,
    span_culling: bool,
}

impl Sil<'_> {
    fn of(&self, s: &Sphere) -> Silhouette {
        let eye = self.camera.eye();
        if self.cone.is_some_and(|c| c.misses(s.center - eye, s.radius)) {
            return Silhouette::NONE;
        }
        if !self.span_culling {
            return Silhouette::ALL;
        }
        let geom = SphereGeom::new(s.center, s.radius, eye, self.scale);
        Silhouette::new(
            geom.l,
            s.radius * self.scale.0,
            self.camera,
            self.margin,
            self.step_err,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec3::Vec3;
    use crate::method::Method;
    use embedded_graphics::pixelcolor::Rgb888;

    fn scene(x: f32, background: Rgb888) -> Scene<2> {
        Scene::from_array(
            [
                Sphere::new(Vec3::new(x, 0.0, 0.0), 0.5, Rgb888::new(255, 64, 64)),
                Sphere::new(Vec3::new(1.0, 0.0, 0.0), 0.5, Rgb888::new(64, 255, 64)),
            ],
            background,
        )
    }

    /// The plans of a still frame, a moved sphere and a frame-wide change, after a first
    /// frame.
    fn plans(method: Method) -> [Changes; 4] {
        let camera = Camera::new(
            Vec3::new(0.0, 0.0, 6.0),
            Vec3::ZERO,
            Vec3::new(0.0, 1.0, 0.0),
            0.6,
            Size::new(64, 64),
        )
        .unwrap();
        let black = Rgb888::new(0, 0, 0);
        let mut shown = Incremental::new();
        let mut update = |s: &Scene<2>| {
            let render: Render<'_, 2, Rgb888> = Render::new(s, &camera).with_method(method);
            shown.update(&render)
        };
        [
            update(&scene(-1.0, black)),
            update(&scene(-1.0, black)),
            update(&scene(-0.9, black)),
            update(&scene(-0.9, Rgb888::new(0, 0, 1))),
        ]
    }

    #[test]
    fn the_rule_traces_what_moved_and_all_on_a_frame_wide_change() {
        for method in [Method::F32, Method::INTEGER] {
            let [first, still, moved, background] = plans(method);
            assert!(first.is_full(), "{method}");
            assert!(!still.is_full() && still.is_empty(), "{method}");
            assert!(!moved.is_full() && !moved.is_empty(), "{method}");
            assert!(moved.traced() < 64 * 64 / 4, "{method}: {}", moved.traced());
            assert!(background.is_full(), "{method}");
        }
    }
}
