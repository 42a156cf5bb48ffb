//! Writing to stdout and stderr without ever panicking (`outln!` panics
//! when stdout is a closed pipe or a full disk).
//!
//! - stdout: every write is flushed at once. A closed pipe (EPIPE, e.g.
//!   `clump check X | head -1`) ends the process quietly with status
//!   [`EXIT_BROKEN_PIPE`] (141 = 128 + SIGPIPE, what a shell reports for a
//!   program ended by a closed pipe). Any other failure (e.g. `> /dev/full`)
//!   prints `error: cannot write to stdout: …` on stderr and exits with 1.
//! - stderr: failures are ignored. Diagnostics, log lines and progress are
//!   a courtesy; a run never stops because they cannot be shown.

use std::fmt;
use std::io::{ErrorKind, Write};

/// Exit status after stdout was closed by its reader.
pub const EXIT_BROKEN_PIPE: u8 = 141;

/// Writes to stdout and flushes; ends the process when stdout fails.
pub fn out(args: fmt::Arguments) {
    let mut o = std::io::stdout().lock();
    if let Err(e) = o.write_fmt(args).and_then(|()| o.flush()) {
        drop(o);
        stdout_failed(&e)
    }
}

/// Ends the process after a failed write to stdout (see the module doc).
pub fn stdout_failed(e: &std::io::Error) -> ! {
    if e.kind() == ErrorKind::BrokenPipe {
        std::process::exit(EXIT_BROKEN_PIPE.into())
    }
    err(format_args!("error: cannot write to stdout: {e}\n"));
    std::process::exit(1)
}

/// Writes to stderr, ignoring failures.
pub fn err(args: fmt::Arguments) {
    let _ = std::io::stderr().lock().write_fmt(args);
}

/// `println!` that never panics (see [`out`]).
macro_rules! outln {
    () => { $crate::term::out(format_args!("\n")) };
    ($($t:tt)*) => { $crate::term::out(format_args!("{}\n", format_args!($($t)*))) };
}

/// `eprint!` that ignores failures (see [`err`]).
macro_rules! err {
    ($($t:tt)*) => { $crate::term::err(format_args!($($t)*)) };
}

/// `eprintln!` that ignores failures (see [`err`]).
macro_rules! errln {
    () => { $crate::term::err(format_args!("\n")) };
    ($($t:tt)*) => { $crate::term::err(format_args!("{}\n", format_args!($($t)*))) };
}
