//! SIGINT, SIGTERM and SIGHUP while a PNG is being made: the unfinished temporary file
//! beside the output is removed, stderr says so, and the exit code is 128 + the signal
//! (130, 143, 129), as a shell reports a process the signal killed.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};

/// The temporary file being written, if any. The main thread holds the lock while it
/// creates the file and while it renames it into place, so a signal handled meanwhile
/// waits and then finds the file there or gone, never half-renamed.
static TEMP: Mutex<Option<PathBuf>> = Mutex::new(None);

/// The lock on the temporary file's name (poisoning cannot leave a wrong name: the
/// name is only ever replaced whole).
pub fn hold() -> MutexGuard<'static, Option<PathBuf>> {
    TEMP.lock().unwrap_or_else(|e| e.into_inner())
}

/// Handles the signals from now on, on a thread of their own; `output` is named in the
/// message.
pub fn install(output: &Path) {
    let output = output.to_path_buf();
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return; // the default action stays: the process ends, as before
    };
    let handler = move || {
        let Some(signal) = signals.forever().next() else {
            return;
        };
        let name = match signal {
            SIGINT => "SIGINT",
            SIGTERM => "SIGTERM",
            _ => "SIGHUP",
        };
        let mut temp = hold();
        let what = match temp.take() {
            Some(path) => match fs::remove_file(&path) {
                Ok(()) => format!(
                    "removed the unfinished temporary file; {} was not written",
                    output.display()
                ),
                Err(e) => format!(
                    "could not remove the unfinished temporary file beside {}: {e}",
                    output.display()
                ),
            },
            None => "no temporary file was open".to_string(),
        };
        // A closed stderr must not stop the exit: no panic on a failed write here.
        let _ = writeln!(std::io::stderr(), "\nertrace: interrupted by {name}: {what}");
        std::process::exit(128 + signal);
    };
    let _ = std::thread::Builder::new()
        .name("ertrace-signals".into())
        .spawn(handler);
}
