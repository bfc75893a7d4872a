//! Desktop preview: a scene file in an SDL window, through the display model the
//! firmware will drive (Rgb888, Rgb565, Gray8/4/2, BinaryColor, with or without the
//! kernel's ordered dither), at the display's real resolution and a pixel scale.
//!
//! ```text
//! cargo run --release -p embedded-raytracer-preview -- scenes/lab.toml \
//!     [--display rgb888|rgb565|gray8|gray4|gray4-dither|gray2|gray2-dither|binary|binary-dither] \
//!     [--size WxH] [--scale N] [--bayer 4|8] [--theme oled-blue|oled-white] \
//!     [--stepping …] [--sphere-test …] [--sqrt …] [--diff] [--no-overlay] \
//!     [--frame K] [--screenshot OUT.png [--frames N]]
//! ```
//!
//! Keys: ←/→ orbit around the look-at point (azimuth, 5° a press), ↑/↓ elevation; left
//! mouse drag orbits too (half a turn per display width); wheel, `+`/`=` and `-` zoom;
//! `R` resets the view; `M`/`Shift+M` next/previous method (all 30 of `Method::ALL`);
//! `I` toggles the arithmetic (f32, or the integer kernel where its per-frame rule
//! takes the frame: `integer/…` in the status bar, `→ f32` where it does not);
//! `E`/`Shift+E` next/previous origin of the shadow and reflection rays (convex, then
//! the textbook fixed epsilon at 1e-3, 1e-6 and 1e-1 scene units: [`view::SECONDARY`]);
//! `A`/`Shift+A` next/previous sampling (`center`, `grid:2…4`, `adaptive:2…4`:
//! `Sampling::ALL`, shown after the model in the status bar);
//! `D` toggles the difference view (pixels where the shown frame differs from the
//! `direct/robust/exact` render with the convex origin, through the same display
//! model, in magenta); `Tab`/`Shift+Tab` or `1`–`9` pick the display model; `B`
//! switches the Bayer matrix 8×8/4×4; `T` switches the OLED theme (blue/white) of the
//! binary models; `Space` pauses and resumes a scene's motion, `.`/`,` pause and step
//! one frame forward/back; `Esc`/`Q` quits.
//!
//! A scene file with `[[motion]]` plays in real time at its `[animation]` frame rate:
//! frame `k` (the moment `k / fps`) is shown from `k / fps` seconds after the start,
//! looping after its `frames`; when drawing is slower, frames are skipped rather than
//! the motion slowed. The frames are drawn onto one framebuffer of the display model
//! through one `Incremental`, as a firmware draws them: only the pixels that can
//! differ from the frame before are traced and sent. A change of view (orbit, zoom,
//! method, sampling, model) is the next frame's, which the incremental rule draws
//! whole; a reload draws the next frame whole. `--frame K` starts paused on frame `K`,
//! the render CLI's `--frame K` (the moment `(K − 1) / fps`). A still scene is drawn
//! whole at each change, so the status bar's time is always a whole frame's.
//!
//! A scene file without lights, planes or mirrors is drawn through the spheres-only
//! type `Scene<N>` (the Lab #1 loop), one with them through the full type with the
//! host's capacities, as the render CLI does: the same file gives the CLI's pixels.
//! The scene file is polled for changes (mtime, four times a second) and reloaded;
//! a file that fails to load leaves the last good scene on screen with the error text
//! over it (with `--no-overlay`, on stderr only). The display resolution is fixed for the session: the file's
//! `camera.width`/`height` at start-up, or `--size`.
//!
//! Below the image, a status bar (omitted with `--no-overlay`) shows the render time
//! of the last frame (the kernel drawing into the model's framebuffer; measured with
//! `Instant` around `Render::draw`), the model and the method, and for a scene with
//! lights, planes or mirrors the secondary rays' origin (`convex`, `eps=1e-3`). For a
//! scene that moves, its third line shows the frame rate achieved and the share of the
//! display's pixels the last frame traced and sent (`25 fps traced 12% sent 10%`), or
//! while paused the frame (`paused 12/30 traced …`). The status bar and the error text
//! are drawn on the window, never on the model's framebuffer the frames are drawn on:
//! they cover no pixel the next frame would have to redraw.
//!
//! Headless: `--screenshot OUT.png` renders one frame and writes it (the window's
//! pixels, with `--scale`) without opening a window or needing a display. With
//! `--frame K` and a scene that moves, frame `K − 1` is drawn first and frame `K` over
//! it through the incremental rule, as the player draws it: the screenshot is then the
//! render CLI's `--frame K` PNG only if that rule is exact.
//! `--screenshot OUT.png --frames N` opens the window, shows N frames, then writes the
//! frame it showed. The simulator's own `EG_SIMULATOR_DUMP=OUT.png` also works: the
//! first frame handed to the window is written and the program exits.
//!
//! The program: [`args`] (the flags), [`loading`] (the scene file, its frames and its
//! reload), [`orbit`] (the user's camera), [`view`] (what decides a frame's pixels),
//! [`play`] (the clock and the framebuffer drawn incrementally), [`app`] (the program
//! state, its keys and mouse, its status bar). The display models are the
//! `embedded-raytracer-display` crate's, which other front ends share.

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics_simulator::{OutputSettings, OutputSettingsBuilder, SimulatorDisplay, Window};

mod app;
mod args;
mod loading;
mod orbit;
mod play;
mod view;

use app::App;
use args::parse_args;

/// Writes the screen as the window shows it (with the pixel scale).
fn save(screen: &SimulatorDisplay<Rgb888>, settings: &OutputSettings, path: &Path) -> Result<(), String> {
    screen
        .to_rgb_output_image(settings)
        .save_png(path)
        .map_err(|e| format!("{}: cannot write the PNG: {e}", path.display()))
}

fn run() -> Result<(), String> {
    let args = match parse_args(std::env::args_os().skip(1)) {
        Ok(args) => args,
        Err(e)
            if matches!(
                e.kind(),
                clap::error::ErrorKind::DisplayHelp | clap::error::ErrorKind::DisplayVersion
            ) =>
        {
            print!("{}", e.render());
            return Ok(());
        }
        // One line: the flag and the reason (clap's first paragraph), exit code 2.
        Err(e) => {
            let text = e.render().to_string();
            let first: Vec<&str> = text
                .lines()
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            let first = first.join(" ");
            return Err(first.strip_prefix("error: ").unwrap_or(&first).to_string());
        }
    };
    let mut app = App::new(&args)?;
    // Default scale: a window about 640 pixels wide.
    let scale = args.scale.unwrap_or((640 / app.size.width).clamp(1, 8));
    let settings = OutputSettingsBuilder::new().scale(scale).build();

    if let (Some(path), None) = (&args.screenshot, args.frames) {
        // Headless: no window, no SDL.
        app.draw_as_played();
        save(&app.screen, &settings, path)?;
        println!("{} -> {}", args.scene.display(), path.display());
        return Ok(());
    }

    let mut window = Window::new("embedded-raytracer", &settings);
    let mut frame = 0u32;
    loop {
        // The window paces the loop (60 a second unless the motion's rate is higher).
        window.set_max_fps(app.animation.fps().ceil().clamp(60.0, 1000.0) as u32);
        app.tick(Instant::now());
        if app.dirty {
            app.redraw();
        }
        // With EG_SIMULATOR_DUMP set, this writes the frame and exits the process.
        window.update(&app.screen);
        frame += 1;
        if let (Some(path), Some(n)) = (&args.screenshot, args.frames) {
            if frame >= n {
                save(&app.screen, &settings, path)?;
                println!(
                    "{} -> {} (after {n} window frames)",
                    args.scene.display(),
                    path.display()
                );
                return Ok(());
            }
        }
        for event in window.events() {
            if !app.handle(event) {
                return Ok(());
            }
        }
        app.poll_file();
    }
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}
