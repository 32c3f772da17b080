//! The `twinray` app above the render library (`twinray_host`): what the commands share that
//! needs crates the library keeps out, a plotting crate and a web server. Its modules are
//! layers too, above every layer of the library (`docs/architecture.md`):
//!
//! - [`bench`](mod@bench): speed against error, with tables, plots and HTML;
//! - [`crosscheck`](mod@crosscheck): twinray's references against Mitsuba 3's renders;
//! - [`view`](mod@view): the live page in the browser (its GPU work runs `twinray` children).
//!
//! The command line itself is the binary (`src/cli/`).

pub mod bench;

pub mod crosscheck;

pub mod view;
