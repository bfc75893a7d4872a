//! Property tests: random valid scenes and cameras never panic, never produce a NaN,
//! write every pixel exactly once, and with the default method match the f64
//! reference except in the undecidable band and within the silhouette tolerance;
//! random invalid inputs give errors; arbitrary scene-file text never panics.
//!
//! Seeded (`RNG_SEED`), so every run tries the same cases; a failure prints the
//! shrunk failing case. Nothing is persisted to disk.

use core::convert::Infallible;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_raytracer::{
    scene_file, CameraError, CameraParams, Method, Render, Scene, SceneError, Sphere, SphereError, Vec3,
};
use embedded_raytracer::{MAX_FOV, MAX_RESOLUTION};
use embedded_raytracer_lab::reference;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

/// The fixed seed of every property here.
const RNG_SEED: u64 = 0x5eed_0003;

fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(RNG_SEED),
        failure_persistence: None,
        ..Config::default()
    }
}

/// The silhouette tolerance of the default method, in radians: a pixel may show a
/// different object than the f64 reference only if its ray passes within this angle
/// of a silhouette (or the two nearest spheres are within this relative depth).
///
/// Why 1e-5: `Incremental` stepping accumulates up to ~0.5 px of drift at 8192 px
/// (a few 1e-6 rad at the image sizes here, see `lab/tests/lab/stability.rs`), and the f32
/// ray, basis and hit distance add a few 1e-7; 1e-5 covers both with a margin. It
/// is 1/100 of a pixel at 1000 px across a 60° field of view.
const SILHOUETTE_TOLERANCE: f64 = 1e-5;

fn coord(range: f32) -> impl Strategy<Value = f32> {
    -range..range
}

fn vec3(range: f32) -> impl Strategy<Value = Vec3> {
    (coord(range), coord(range), coord(range)).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn color() -> impl Strategy<Value = Rgb888> {
    any::<(u8, u8, u8)>().prop_map(|(r, g, b)| Rgb888::new(r, g, b))
}

fn scene() -> impl Strategy<Value = Scene<6>> {
    (
        proptest::collection::vec((vec3(20.0), 0.05f32..5.0, color()), 0..=6),
        color(),
    )
        .prop_map(|(spheres, background)| {
            let mut scene = Scene::new(background);
            for (c, r, col) in spheres {
                scene.push(Sphere::new(c, r, col)).unwrap();
            }
            scene
        })
}

fn camera_params() -> impl Strategy<Value = CameraParams> {
    (
        vec3(20.0),
        vec3(20.0),
        vec3(1.0),
        0.05f32..2.8,
        proptest::option::of(0.05f32..2.8),
        1u32..=32,
        1u32..=32,
    )
        .prop_map(|(eye, look_at, up, fov_y, fov_x, w, h)| CameraParams {
            eye,
            look_at,
            up,
            fov_y,
            fov_x,
            size: Size::new(w, h),
        })
}

/// A draw target that counts how often each pixel is written.
struct Counter {
    size: Size,
    counts: Vec<u32>,
    outside: usize,
}

impl Counter {
    fn new(size: Size) -> Self {
        Self {
            size,
            counts: vec![0; (size.width * size.height) as usize],
            outside: 0,
        }
    }
}

impl OriginDimensions for Counter {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Counter {
    type Color = Rgb888;
    type Error = Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(&mut self, pixels: I) -> Result<(), Infallible> {
        for Pixel(p, _) in pixels {
            let inside =
                p.x >= 0 && p.y >= 0 && (p.x as u32) < self.size.width && (p.y as u32) < self.size.height;
            if inside {
                self.counts[p.y as usize * self.size.width as usize + p.x as usize] += 1;
            } else {
                self.outside += 1;
            }
        }
        Ok(())
    }
}

proptest! {
    #![proptest_config(config(256))]

    /// Every method, every valid random scene and camera: no panic, no NaN, every
    /// pixel traced and drawn exactly once (also placed at an offset on a smaller,
    /// clipping target).
    #[test]
    fn valid_inputs_render_cleanly(scene in scene(), params in camera_params(), ox in -30i32..30, oy in -30i32..30) {
        let Ok(camera) = params.build() else {
            // Random up/look-at can be (nearly) parallel: the error is the answer.
            return Ok(());
        };
        let (w, h) = (params.size.width, params.size.height);
        for method in Method::ALL {
            let render = Render::<6, Rgb888>::new(&scene, &camera).with_method(method);
            let mut seen = vec![0u32; (w * h) as usize];
            render.trace(|s| {
                assert!(s.direction.is_finite(), "{method}: direction {:?}", s.direction);
                if let Some(hit) = s.hit {
                    assert!(hit.t.is_finite() && hit.t > 0.0, "{method}: t = {}", hit.t);
                    assert!(hit.index < scene.spheres().len());
                }
                seen[s.pixel.y as usize * w as usize + s.pixel.x as usize] += 1;
            });
            prop_assert!(seen.iter().all(|&n| n == 1), "{}: trace counts {:?}", method, seen);

            let mut target = Counter::new(params.size);
            render.draw(&mut target).unwrap();
            prop_assert!(target.counts.iter().all(|&n| n == 1) && target.outside == 0, "{}: draw counts {:?}", method, target.counts);

            // Offset onto a 16×16 target: visible pixels exactly once, nothing outside.
            let mut small = Counter::new(Size::new(16, 16));
            render.with_offset(Point::new(ox, oy)).draw(&mut small).unwrap();
            prop_assert_eq!(small.outside, 0);
            for y in 0..16i32 {
                for x in 0..16i32 {
                    let (i, j) = (x - ox, y - oy);
                    let covered = i >= 0 && j >= 0 && (i as u32) < w && (j as u32) < h;
                    let n = small.counts[(y * 16 + x) as usize];
                    prop_assert_eq!(n, u32::from(covered), "{} offset ({}, {}) pixel ({}, {})", method, ox, oy, x, y);
                }
            }
        }
    }

    /// The default method against the f64 reference: coverage errors only within
    /// SILHOUETTE_TOLERANCE of a silhouette or depth tie; shading within one level
    /// wherever both show the same sphere away from silhouettes.
    #[test]
    fn default_method_matches_the_reference(scene in scene(), mut params in camera_params(), aim in any::<prop::sample::Index>()) {
        // Aim at a sphere (most random cameras would otherwise see only background).
        if !scene.spheres().is_empty() {
            params.look_at = aim.get(scene.spheres()).center;
        }
        let Ok(camera) = params.build() else { return Ok(()); };
        let truth = reference::render(&scene, &camera);
        let m = reference::compare(&Render::<6, Rgb888>::new(&scene, &camera), &truth);
        prop_assert_eq!(m.non_finite, 0);
        prop_assert_eq!(m.bad_samples, 0);
        prop_assert!(
            m.worst_error_margin <= SILHOUETTE_TOLERANCE,
            "{} coverage errors, worst {:e} from a silhouette/tie: {:?}", m.coverage_errors, m.worst_error_margin, m
        );
        prop_assert!(m.drift_max < 0.01, "drift {}", m.drift_max);
        prop_assert!(m.shade_max <= 1, "shade error {} levels: {:?}", m.shade_max, m);
    }

    /// Arbitrary camera numbers (NaN, ∞, zero, huge): `build` returns, never panics,
    /// and whatever it accepts renders without NaN.
    #[test]
    fn arbitrary_camera_numbers_never_panic(
        v in proptest::collection::vec(prop_oneof![any::<f32>(), -10f32..10.0, Just(0.0f32), Just(f32::NAN)], 11),
        w in 0u32..10_000, h in 0u32..10_000, with_fov_x in any::<bool>(),
    ) {
        let p = CameraParams {
            eye: Vec3::new(v[0], v[1], v[2]),
            look_at: Vec3::new(v[3], v[4], v[5]),
            up: Vec3::new(v[6], v[7], v[8]),
            fov_y: v[9],
            fov_x: with_fov_x.then_some(v[10]),
            size: Size::new(w % 40, h % 40),
        };
        if let Ok(camera) = p.build() {
            let mut scene: Scene<1> = Scene::new(Rgb888::BLACK);
            scene.push(Sphere::new(Vec3::ZERO, 1.0, Rgb888::WHITE)).unwrap();
            Render::<1, Rgb888>::new(&scene, &camera).trace(|s| {
                assert!(s.direction.is_finite(), "{:?}", s.direction);
                assert!(s.hit.is_none_or(|h| h.t.is_finite()));
            });
        }
        let big = CameraParams { size: Size::new(w, h), ..p };
        let _ = big.build();
    }

    /// Definitely invalid inputs give the matching error.
    #[test]
    fn invalid_inputs_give_errors(
        eye in vec3(100.0), look_at in vec3(100.0), up in vec3(1.0),
        bad in prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY)],
        which in 0usize..3, fov in 0.1f32..2.0, neg_fov in -10f32..=0.0, wide in (MAX_FOV + 0.01)..100.0,
        big in (MAX_RESOLUTION + 1)..u32::MAX, radius in -100f32..=0.0,
    ) {
        let good = CameraParams::new(eye, look_at, up, fov, Size::new(8, 8));
        let mut nan = good;
        match which {
            0 => nan.eye.x = bad,
            1 => nan.look_at.y = bad,
            _ => nan.up.z = bad,
        }
        prop_assert!(matches!(nan.build(), Err(CameraError::NotFinite(_))));
        prop_assert_eq!(CameraParams { look_at: eye, ..good }.build(), Err(CameraError::EyeAtLookAt));
        // The basis is checked before the field of view: either error is right.
        let basis_or_fov = |r: Result<_, CameraError>| {
            matches!(r, Err(CameraError::FovOutOfRange(_) | CameraError::EyeAtLookAt | CameraError::UpParallelToView))
        };
        let narrow = CameraParams { fov_y: neg_fov, ..good }.build();
        prop_assert!(basis_or_fov(narrow), "{:?}", narrow);
        let wide = CameraParams { fov_y: wide, ..good }.build();
        prop_assert!(basis_or_fov(wide), "{:?}", wide);
        prop_assert_eq!(CameraParams { size: Size::new(0, 8), ..good }.build(), Err(CameraError::ZeroResolution));
        prop_assert_eq!(CameraParams { size: Size::new(8, big), ..good }.build(), Err(CameraError::ResolutionTooLarge));
        prop_assert_eq!(Sphere::try_new(eye, radius, Rgb888::WHITE), Err(SphereError::RadiusNotPositive));
        prop_assert_eq!(Sphere::try_new(eye, bad, Rgb888::WHITE), Err(SphereError::NotFinite));
        let mut scene: Scene<1> = Scene::new(Rgb888::BLACK);
        prop_assert_eq!(scene.push(Sphere::new(look_at, radius, Rgb888::WHITE)), Err(SceneError::Sphere(SphereError::RadiusNotPositive)));
        scene.push(Sphere::new(look_at, 1.0, Rgb888::WHITE)).unwrap();
        prop_assert_eq!(scene.push(Sphere::new(eye, 1.0, Rgb888::WHITE)), Err(SceneError::Full { capacity: 1 }));
    }
}

/// A valid scene file, the seed of the mutation strategy below.
const GOOD: &str = "background = [10, 20, 30]\n[camera]\neye = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\nfov_y_deg = 60.0\nwidth = 32\nheight = 24\n[[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\ncolor = [255, 64, 64]\n";

/// The error contract of `scene_file::parse`: it names a field or a line.
fn check_parse(text: &str) -> Result<(), TestCaseError> {
    match scene_file::parse::<4, 0, 0, 0>(text) {
        Ok(f) => {
            prop_assert!(f.scene.spheres().len() <= 4);
        }
        Err(e) => {
            prop_assert!(
                e.field.is_some() || e.line.is_some(),
                "no field and no line: {:?} for {:?}",
                e,
                text
            );
            prop_assert!(!e.reason.is_empty());
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(512))]

    /// Arbitrary strings never panic the parser.
    #[test]
    fn scene_file_arbitrary_strings(text in any::<String>()) {
        check_parse(&text)?;
    }

    /// Arbitrary bytes (lossily decoded, as a file read would fail on invalid UTF-8).
    #[test]
    fn scene_file_arbitrary_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..256)) {
        check_parse(&String::from_utf8_lossy(&bytes))?;
    }

    /// A valid file with random edits (a byte range replaced by random text): the
    /// interesting inputs are near-valid ones.
    #[test]
    fn scene_file_mutations(start in 0usize..GOOD.len(), len in 0usize..12, insert in "[ -~\n]{0,12}") {
        let mut text = String::from(GOOD);
        let start = (0..=start).rev().find(|&i| text.is_char_boundary(i)).unwrap_or(0);
        let end = (start + len).min(text.len());
        text.replace_range(start..end, &insert);
        check_parse(&text)?;
    }
}
