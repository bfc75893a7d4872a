//! Incremental frames: after any sequence of them the display equals the last frame's
//! full render, bit for bit — every method, sampling and arithmetic, in 16-bit, 24-bit
//! and 1-bit colour, whole, offset and clipped — and they trace and send less than the
//! whole frame.

use embedded_graphics::pixelcolor::{BinaryColor, Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_raytracer::{
    Arithmetic, Camera, CameraParams, Incremental, Light, Material, Method, Plane, Render, Sampling, Scene,
    Settings, Sphere, SubSamples, Vec3,
};

use crate::common::Rng;
use crate::framebuffer::Buffer;

const SIZE: Size = Size::new(40, 32);

fn camera(rng: &mut Rng) -> Camera {
    let eye = Vec3::new(rng.range(-2.0, 2.0), rng.range(0.5, 3.0), rng.range(6.0, 9.0));
    CameraParams::new(
        eye,
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        rng.range(0.5, 1.0),
        SIZE,
    )
    .build()
    .unwrap()
}

fn color(rng: &mut Rng) -> Rgb888 {
    Rgb888::new(
        (rng.next() * 255.0) as u8,
        (rng.next() * 255.0) as u8,
        (rng.next() * 255.0) as u8,
    )
}

fn sphere(rng: &mut Rng) -> Sphere {
    Sphere::new(rng.vec(2.0), rng.range(0.2, 1.0), color(rng))
}

/// One random motion of the scene: a sphere moved a little or far, resized, recoloured,
/// given a `-0.0` coordinate, or nothing.
fn motion<const N: usize, const L: usize, const P: usize, const D: usize>(
    rng: &mut Rng,
    scene: &mut Scene<N, L, P, D>,
) {
    let n = scene.spheres().len();
    let k = ((rng.next() * n as f32) as usize).min(n - 1);
    let mut s = scene.spheres()[k];
    match (rng.next() * 6.0) as u32 {
        0 => s.center += rng.vec(0.05),
        1 => s.center += rng.vec(1.0),
        2 => s.radius = rng.range(0.2, 1.0),
        3 => s.color = color(rng),
        4 => s.center.x = if s.center.x == 0.0 { -0.0 } else { 0.0 },
        _ => return,
    }
    scene.set_sphere(k, s).unwrap();
}

/// Draws `frames` incremental frames of random motions onto a target, and checks it
/// equals the last frame's full render drawn onto a fresh target of the same start.
#[allow(clippy::too_many_arguments)]
fn check_sequence<C, const N: usize, const L: usize, const P: usize, const D: usize>(
    rng: &mut Rng,
    mut scene: Scene<N, L, P, D>,
    camera: &Camera,
    method: Method,
    sampling: Sampling,
    offset: Point,
    clip: Option<Rectangle>,
    fill: C,
    frames: usize,
) -> (usize, usize)
where
    C: PixelColor + From<Rgb888> + core::fmt::Debug,
{
    let target_size = Size::new(SIZE.width + 8, SIZE.height + 6);
    let mut display = Buffer::new(target_size, fill);
    let mut shown = Incremental::new();
    fn render<'a, C, const N: usize, const L: usize, const P: usize, const D: usize>(
        scene: &'a Scene<N, L, P, D>,
        camera: &'a Camera,
        (method, sampling, offset): (Method, Sampling, Point),
    ) -> Render<'a, N, C, L, P, D> {
        Render::new(scene, camera)
            .with_method(method)
            .with_sampling(sampling)
            .with_offset(offset)
    }
    let how = (method, sampling, offset);
    let (mut traced, mut sent) = (0, 0);
    for f in 0..frames {
        if f > 0 {
            motion(rng, &mut scene);
        }
        let stats = shown
            .draw(&render(&scene, camera, how), display.clipped_to(clip))
            .unwrap();
        assert!(stats.refused.is_none());
        if f > 0 {
            traced += stats.traced as usize;
            sent += stats.sent as usize;
        }
    }
    let mut full = Buffer::new(target_size, fill);
    render(&scene, camera, how).draw(full.clipped_to(clip)).unwrap();
    let diff = display.px.iter().zip(&full.px).filter(|(a, b)| a != b).count();
    assert_eq!(
        diff, 0,
        "{diff} pixels differ from the full render: {method} {sampling:?} offset {offset:?} clip {clip:?}"
    );
    (traced, sent)
}

fn samplings() -> [Sampling; 3] {
    let two = SubSamples::new(2).unwrap();
    [Sampling::Center, Sampling::Grid(two), Sampling::Adaptive(two)]
}

#[test]
fn lab1_sequences_equal_the_full_render_for_every_method() {
    let mut rng = Rng(0x1234_5678);
    let (mut traced, mut frames) = (0, 0);
    for case in 0..6 {
        let camera = camera(&mut rng);
        let mut scene: Scene<4> = Scene::new(Rgb888::new(10, 20, 30));
        for _ in 0..4 {
            scene.push(sphere(&mut rng)).unwrap();
        }
        for method in Method::ALL.iter().copied().chain([Method::INTEGER]) {
            let (t, _) = check_sequence(
                &mut rng,
                scene.clone(),
                &camera,
                method,
                Sampling::Center,
                Point::zero(),
                None,
                Rgb565::BLUE,
                5,
            );
            traced += t;
            frames += 4;
        }
        // Offset and clipped, in other colour formats.
        let offset = Point::new(case % 5, 3);
        let clip = Rectangle::new(Point::new(6, 2), Size::new(25, 30));
        check_sequence(
            &mut rng,
            scene.clone(),
            &camera,
            Method::F32,
            Sampling::Center,
            offset,
            Some(clip),
            Rgb888::WHITE,
            6,
        );
        check_sequence(
            &mut rng,
            scene.clone(),
            &camera,
            Method::INTEGER,
            Sampling::Center,
            offset,
            None,
            BinaryColor::On,
            6,
        );
        check_sequence(
            &mut rng,
            scene.clone(),
            &camera,
            Method::F32,
            Sampling::Center,
            offset,
            Some(clip),
            BinaryColor::On,
            6,
        );
    }
    // The work follows the change: on average far less than whole frames.
    assert!(
        traced < frames * (SIZE.width * SIZE.height) as usize,
        "traced {traced} in {frames} frames"
    );
}

#[test]
fn anti_aliased_sequences_equal_the_full_render() {
    let mut rng = Rng(0x9e37_79b9);
    for _ in 0..4 {
        let camera = camera(&mut rng);
        let mut scene: Scene<3> = Scene::new(Rgb888::new(0, 0, 0));
        for _ in 0..3 {
            scene.push(sphere(&mut rng)).unwrap();
        }
        for sampling in samplings() {
            for method in [Method::F32, Method::ALL[0], Method::INTEGER] {
                check_sequence(
                    &mut rng,
                    scene.clone(),
                    &camera,
                    method,
                    sampling,
                    Point::new(2, 1),
                    None,
                    Rgb888::BLACK,
                    5,
                );
            }
        }
    }
}

/// A lit scene: a checkered floor, one or two lights, shadows, a mirror sphere.
fn lit_scene(rng: &mut Rng, mirror: bool, lights: usize) -> Scene<3, 2, 1, 2> {
    let mut scene: Scene<3, 2, 1, 2> = Scene::new(Rgb888::new(40, 60, 90));
    for k in 0..3 {
        let mut s = sphere(rng);
        s.center.y = s.center.y.abs() + s.radius - 0.9;
        if mirror && k == 2 {
            s = s.with_material(Material::new(0.5, 32.0, 0.6));
        }
        scene.push(s).unwrap();
    }
    scene
        .push_plane(
            Plane::new(
                Vec3::new(0.0, -1.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
                Rgb888::new(200, 200, 200),
            )
            .with_checker(Rgb888::new(40, 40, 40), 0.7),
        )
        .unwrap();
    scene
        .push_light(Light::directional(Vec3::new(-1.0, -2.0, -0.5), 0.8))
        .unwrap();
    if lights > 1 {
        scene
            .push_light(Light::point(Vec3::new(2.0, 4.0, 3.0), 0.6))
            .unwrap();
    }
    scene
        .set_settings(Settings::DEFAULT.with_shadows(rng.next() < 0.8))
        .unwrap();
    scene
}

#[test]
fn lit_sequences_equal_the_full_render() {
    let mut rng = Rng(0x0bad_cafe);
    for case in 0..24 {
        let camera = camera(&mut rng);
        let scene = lit_scene(&mut rng, case % 2 == 1, 1 + case % 2);
        for sampling in samplings() {
            let method = if case % 3 == 0 {
                Method::ALL[case]
            } else {
                Method::F32
            };
            check_sequence(
                &mut rng,
                scene.clone(),
                &camera,
                method,
                sampling,
                Point::new(1, 2),
                None,
                Rgb565::BLACK,
                5,
            );
        }
    }
}

/// Draws `render` through `shown` onto `display` cut to `clip` and checks that its
/// windows, row by row, are the runs of `planner`'s plan of the same frame
/// (`Changes::runs`) within the target: a strip's sink, which asks only its rectangle's
/// regions near its columns, sends the runs the whole plan has, merged alike. Or, for a
/// frame the integer kernel draws, that each window is a strip it traced (as many
/// windows as strips, their pixels the traced ones), none overlapping another, and
/// every run inside one; `true` then.
fn check_windows<const N: usize, const L: usize, const P: usize, const D: usize>(
    (shown, planner): (&mut Incremental<N, L, P, D>, &mut Incremental<N, L, P, D>),
    render: &Render<'_, N, Rgb565, L, P, D>,
    display: &mut Buffer<Rgb565>,
    clip: Rectangle,
) -> bool {
    let changes = planner.update(render);
    display.windows.clear();
    let stats = shown.draw(render, display.clipped_to(Some(clip))).unwrap();
    let mut sent: Vec<_> = display
        .windows
        .iter()
        .map(|w| (w.top_left.y, w.top_left.x, w.size.width, w.size.height))
        .collect();
    sent.sort_unstable();
    let (x0, x1) = (clip.top_left.x as u32, clip.top_left.x as u32 + clip.size.width);
    let rows = clip.top_left.y as u32..clip.top_left.y as u32 + clip.size.height;
    let runs: Vec<_> = rows
        .flat_map(|j| {
            changes
                .runs(j)
                .map(move |(lo, hi)| (lo.max(x0), hi.min(x1)))
                .filter(|(lo, hi)| lo < hi)
                .map(move |(lo, hi)| (j as i32, lo as i32, hi - lo, 1))
        })
        .collect();
    let what = format!("{} {:?} clip {clip:?}", render.method(), render.sampling());
    if stats.arithmetic == Arithmetic::Integer && sent != runs {
        let pixels: u32 = sent.iter().map(|w| w.2 * w.3).sum();
        assert_eq!(
            (sent.len() as u32, pixels),
            (stats.strips, stats.traced),
            "{what}"
        );
        assert_eq!(
            (stats.windows, stats.sent),
            (stats.strips, stats.traced),
            "{what}"
        );
        let holds = |w: &(i32, i32, u32, u32), (y, x0, x1): (i32, i32, i32)| {
            w.0 <= y && y < w.0 + w.3 as i32 && w.1 <= x0 && x1 <= w.1 + w.2 as i32
        };
        for (k, a) in sent.iter().enumerate() {
            for b in &sent[k + 1..] {
                let apart = a.0 + a.3 as i32 <= b.0 || b.0 + b.3 as i32 <= a.0;
                assert!(
                    apart || a.1 + a.2 as i32 <= b.1 || b.1 + b.2 as i32 <= a.1,
                    "{what}: {a:?} {b:?}"
                );
            }
        }
        for r in &runs {
            let run = (r.0, r.1, r.1 + r.2 as i32);
            assert!(
                sent.iter().any(|w| holds(w, run)),
                "{what}: run {r:?} in no window of {sent:?}"
            );
        }
        return true;
    }
    assert_eq!(sent, runs, "{what}");
    let pixels: u32 = runs.iter().map(|r| r.2).sum();
    assert_eq!((stats.sent, stats.windows as usize), (pixels, runs.len()));
    false
}

#[test]
fn the_windows_sent_are_the_runs() {
    let mut rng = Rng(0x5eed_0f70);
    let mut strips = 0;
    for case in 0..8 {
        let camera = camera(&mut rng);
        let mut scene: Scene<4> = Scene::new(Rgb888::new(10, 20, 30));
        for _ in 0..4 {
            scene.push(sphere(&mut rng)).unwrap();
        }
        // The whole image, and a target that cuts the strips at odd columns.
        let x = 3 + case;
        let cut = Rectangle::new(Point::new(x, 2), Size::new(SIZE.width - 2 * x as u32, 25));
        let mut display = Buffer::new(SIZE, Rgb565::BLACK);
        for method in [Method::F32, Method::INTEGER] {
            for sampling in samplings() {
                for clip in [Rectangle::new(Point::zero(), SIZE), cut] {
                    let mut scene = scene.clone();
                    let mut two = (Incremental::new(), Incremental::new());
                    for f in 0..6 {
                        if f > 0 {
                            motion(&mut rng, &mut scene);
                        }
                        let render = Render::new(&scene, &camera)
                            .with_method(method)
                            .with_sampling(sampling);
                        strips += usize::from(check_windows(
                            (&mut two.0, &mut two.1),
                            &render,
                            &mut display,
                            clip,
                        ));
                    }
                }
            }
        }
        let mut lit = lit_scene(&mut rng, case % 2 == 1, 1 + case as usize % 2);
        let mut two = (Incremental::new(), Incremental::new());
        for f in 0..6 {
            if f > 0 {
                motion(&mut rng, &mut lit);
            }
            check_windows(
                (&mut two.0, &mut two.1),
                &Render::new(&lit, &camera),
                &mut display,
                cut,
            );
        }
    }
    // The integer kernel's frames sent their strips whole.
    assert!(strips > 50, "{strips} integer frames sent strips");
}

/// Two spheres side by side a few pixels apart, joined into one rectangle by a third
/// above them, all three recoloured: in their middle rows the two runs merge across the
/// gap, and a target whose edge falls in the gap gets the merged run's part of it.
#[test]
fn a_target_cut_in_a_merged_gap_gets_its_part() {
    let camera = CameraParams::new(
        Vec3::new(0.0, 0.0, 8.0),
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        0.6,
        SIZE,
    )
    .build()
    .unwrap();
    let mut display = Buffer::new(SIZE, Rgb565::BLACK);
    for step in 0..12 {
        let half = 0.5 + 0.05 * step as f32;
        let red = Rgb888::new(200, 40, 40);
        let at = |x: f32, y: f32, r: f32| Sphere::new(Vec3::new(x, y, 0.0), r, red);
        let before: Scene<3> = Scene::from_array(
            [at(-half, 0.0, 0.5), at(half, 0.0, 0.5), at(0.0, 0.95, 0.6)],
            Rgb888::BLACK,
        );
        let mut after = before.clone();
        for k in 0..3 {
            let s = after.spheres()[k];
            after
                .set_sphere(
                    k,
                    Sphere {
                        color: Rgb888::new(40, 200, 40),
                        ..s
                    },
                )
                .unwrap();
        }
        let edges = (1..SIZE.width as i32).flat_map(|x| {
            [
                Rectangle::new(Point::zero(), Size::new(x as u32, SIZE.height)),
                Rectangle::new(Point::new(x, 0), Size::new(SIZE.width - x as u32, SIZE.height)),
            ]
        });
        for clip in edges {
            let mut two = (Incremental::new(), Incremental::new());
            for scene in [&before, &after] {
                let render = Render::new(scene, &camera);
                check_windows((&mut two.0, &mut two.1), &render, &mut display, clip);
            }
        }
    }
}

#[test]
fn nothing_moved_sends_nothing_and_a_lost_area_is_redrawn() {
    let mut rng = Rng(7);
    let camera = camera(&mut rng);
    let scene = lit_scene(&mut rng, false, 1);
    let render = Render::new(&scene, &camera);
    let mut display = Buffer::new(SIZE, Rgb565::BLACK);
    let mut shown = Incremental::new();
    assert!(shown.draw(&render, &mut display).unwrap().full);
    let calls = display.calls;
    let again = shown.draw(&render, &mut display).unwrap();
    assert_eq!(
        (again.traced, again.sent, again.windows, again.full),
        (0, 0, 0, false)
    );
    assert_eq!(display.calls, calls);

    // An overlay drawn over the picture, then told: that rectangle alone is redrawn.
    let overlay = Rectangle::new(Point::new(3, 4), Size::new(10, 7));
    display.fill_solid(&overlay, Rgb565::RED).unwrap();
    shown.invalidate_area(overlay);
    let redraw = shown.draw(&render, &mut display).unwrap();
    assert_eq!((redraw.sent, redraw.full), (70, false));
    let mut full = Buffer::new(SIZE, Rgb565::BLACK);
    render.draw(&mut full).unwrap();
    assert!(display.px == full.px);

    // A frame-wide change (the camera) draws the whole frame.
    let moved = CameraParams {
        eye: camera.eye() + Vec3::new(0.1, 0.0, 0.0),
        ..*camera.params()
    }
    .build()
    .unwrap();
    assert!(
        shown
            .draw(&Render::new(&scene, &moved), &mut display)
            .unwrap()
            .full
    );
}

#[test]
fn bands_learn_the_changed_runs_and_trace_only_them() {
    let mut rng = Rng(99);
    let camera = camera(&mut rng);
    let mut scene: Scene<3> = Scene::new(Rgb888::new(0, 0, 0));
    for _ in 0..3 {
        scene.push(sphere(&mut rng)).unwrap();
    }
    let width = SIZE.width as usize;
    // The display: a buffer the "DMA" copies the changed runs into.
    let mut display = vec![Rgb565::BLACK; width * SIZE.height as usize];
    let mut shown: Incremental<3> = Incremental::new();
    let mut band = vec![Rgb565::BLACK; width * 8];
    for f in 0..8 {
        if f > 0 {
            motion(&mut rng, &mut scene);
        }
        let render = Render::new(&scene, &camera);
        let changes = shown.update(&render);
        assert_eq!(changes.is_full(), f == 0);
        for j0 in (0..SIZE.height).step_by(8) {
            let rows = j0..(j0 + 8).min(SIZE.height);
            let band = &mut band[..width * rows.len()];
            changes.draw_band(&render, rows.clone(), band).unwrap();
            for j in rows {
                for (lo, hi) in changes.runs(j) {
                    let (lo, hi) = (lo as usize, hi as usize);
                    let row = (j - j0) as usize * width;
                    display[j as usize * width + lo..j as usize * width + hi]
                        .copy_from_slice(&band[row + lo..row + hi]);
                }
            }
        }
        let mut full = vec![Rgb565::BLACK; width * SIZE.height as usize];
        Render::new(&scene, &camera)
            .draw_band(0..SIZE.height, &mut full)
            .unwrap();
        assert!(
            display == full,
            "frame {f}: the runs sent do not make the full frame"
        );
    }
}

/// Shadows' edges at a resolution where they are sharp: a ball above a checkered floor
/// under a low directional light, a point light or both, moved a little each frame
/// (rising, sliding, sinking into the floor); every frame's display equals its full
/// render, and frames trace much less than the whole image.
#[test]
fn moving_shadows_are_redrawn_exactly() {
    let mut rng = Rng(0x51ad_0e55);
    let size = Size::new(128, 96);
    let (mut traced, mut frames) = (0u64, 0u64);
    for case in 0..12 {
        let eye = Vec3::new(rng.range(-3.0, 3.0), rng.range(0.6, 4.0), rng.range(5.0, 9.0));
        let camera = CameraParams::new(eye, Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), 0.8, size)
            .build()
            .unwrap();
        let mut scene: Scene<3, 2, 1, 0> = Scene::new(Rgb888::new(30, 40, 60));
        let ball = Sphere::new(Vec3::new(0.0, 0.6, 0.0), 0.5, Rgb888::new(220, 60, 50))
            .with_material(Material::new(0.5, 32.0, 0.0));
        scene.push(ball).unwrap();
        scene
            .push(Sphere::new(
                Vec3::new(-1.6, 0.4, -0.8),
                0.4,
                Rgb888::new(60, 200, 90),
            ))
            .unwrap();
        scene
            .push(Sphere::new(
                Vec3::new(1.5, 0.3, 0.6),
                0.3,
                Rgb888::new(70, 110, 240),
            ))
            .unwrap();
        scene
            .push_plane(
                Plane::new(Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), Rgb888::new(220, 220, 210))
                    .with_checker(Rgb888::new(60, 60, 70), 0.5),
            )
            .unwrap();
        if case % 3 != 1 {
            let low = rng.range(-1.2, -0.25);
            let dir = Vec3::new(rng.range(-1.0, 1.0), low, rng.range(-1.0, 1.0));
            scene.push_light(Light::directional(dir, 0.8)).unwrap();
        }
        if case % 3 != 0 {
            let at = Vec3::new(rng.range(-3.0, 3.0), rng.range(1.5, 4.0), rng.range(-3.0, 3.0));
            scene.push_light(Light::point(at, 0.7)).unwrap();
        }
        let method = if case % 4 == 3 {
            Method::ALL[case * 5 % Method::ALL.len()]
        } else {
            Method::F32
        };
        let mut display = Buffer::new(size, Rgb565::BLACK);
        let mut shown = Incremental::new();
        let step = Vec3::new(
            rng.range(-0.04, 0.04),
            rng.range(-0.05, 0.05),
            rng.range(-0.04, 0.04),
        );
        for f in 0..8 {
            let mut b = ball;
            b.center = ball.center + step * f as f32;
            scene.set_sphere(0, b).unwrap();
            let render = Render::new(&scene, &camera).with_method(method);
            let stats = shown.draw(&render, &mut display).unwrap();
            assert!(stats.refused.is_none());
            if f > 0 {
                assert!(!stats.full, "case {case} frame {f}: drawn whole");
                traced += u64::from(stats.traced);
                frames += 1;
            }
            let mut full = Buffer::new(size, Rgb565::BLACK);
            render.draw(&mut full).unwrap();
            let diff = display.px.iter().zip(&full.px).filter(|(a, b)| a != b).count();
            assert_eq!(
                diff, 0,
                "case {case} frame {f} ({method}): {diff} pixels differ from the full render"
            );
        }
    }
    let whole = u64::from(size.width * size.height);
    assert!(
        traced < frames * whole / 3,
        "traced {traced} px in {frames} frames of {whole}"
    );
}
