//! The GPU work of the page, each piece a `twinray` child process: a crash in a driver, a
//! stage that never returns or a validation error ends that child, with its words, and never
//! the server. One child at a time holds the GPU (`Jobs::gpu`), so timings are not shared.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::time::Duration;
use tokio::process::Command;
use tokio::sync::Mutex;

/// How a child is run: the binary, the flags every child gets (the global ones `view` was
/// given), and the wall-clock backstop past the GPU deadline each child keeps itself.
pub struct Jobs {
    pub twinray: PathBuf,
    pub global: Vec<String>,
    pub backstop: Duration,
    pub gpu: Mutex<()>,
}

/// Which still image: the scene, its size, frame and camera.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Shot {
    pub width: u32,
    pub height: u32,
    pub frame: u32,
    pub eye: Option<[f32; 3]>,
    pub look_at: Option<[f32; 3]>,
}

impl Shot {
    fn args(&self) -> Vec<String> {
        let point = |p: [f32; 3]| format!("{},{},{}", p[0], p[1], p[2]);
        let mut args = vec!["--width".into(), self.width.to_string(), "--height".into(), self.height.to_string()];
        args.extend(["--frame".into(), self.frame.to_string()]);
        args.extend(self.eye.map(|p| ["--eye".into(), point(p)]).into_iter().flatten());
        args.extend(self.look_at.map(|p| ["--look-at".into(), point(p)]).into_iter().flatten());
        args
    }
}

/// Two renders and their difference, as `twinray compare` wrote them, with its JSON report.
pub struct Compared {
    pub report: Value,
    pub a: Vec<u8>,
    pub b: Vec<u8>,
    pub diff: Vec<u8>,
}

/// Why a child gave no result: its words (the error it printed and what its exit means).
#[derive(Debug)]
pub struct Failed(pub String);

/// How hard `compare` times: one cold trace while editing, or an interval over placements.
#[derive(Clone, Copy)]
pub enum Timing {
    Once,
    Interval,
}

impl Jobs {
    /// `twinray compare` of specs `a` and `b` at `shot`, its images read back from `scratch`
    /// (removed after).
    pub async fn compare(
        &self,
        scene: Option<&str>,
        (a, b): (&str, &str),
        shot: &Shot,
        timing: Timing,
        scratch: &Path,
    ) -> Result<Compared, Failed> {
        let mut args: Vec<String> = vec!["compare".into()];
        args.extend(scene.map(String::from));
        args.extend(["--a".into(), a.into(), "--b".into(), b.into()]);
        args.extend(["--out-dir".into(), scratch.display().to_string(), "--json".into()]);
        let traces = match timing {
            Timing::Once => ["1", "0", "1"],
            Timing::Interval => ["10", "2", "6"],
        };
        for (flag, n) in ["--runs", "--warmup", "--placements"].into_iter().zip(traces) {
            args.extend([flag.into(), n.into()]);
        }
        args.extend(shot.args());
        let stdout = self.run(&args).await;
        let read = |name: &str| std::fs::read(scratch.join(name));
        let result = stdout.and_then(|out| {
            let report = serde_json::from_str(out.trim()).map_err(|e| Failed(format!("compare's report: {e}")))?;
            let images = (read("a.png"), read("b.png"), read("diff.png"));
            match images {
                (Ok(a), Ok(b), Ok(diff)) => Ok(Compared { report, a, b, diff }),
                _ => Err(Failed(format!("compare wrote no images in {}", scratch.display()))),
            }
        });
        let _ = std::fs::remove_dir_all(scratch);
        result
    }

    /// `twinray explain --json` of pixel (x, y) of `shot`.
    pub async fn explain(
        &self,
        scene: Option<&str>,
        (a, b): (&str, &str),
        shot: &Shot,
        (x, y): (u32, u32),
    ) -> Result<Value, Failed> {
        let mut args: Vec<String> = vec!["explain".into()];
        args.extend(scene.map(String::from));
        args.extend(["--pixel".into(), format!("{x},{y}")]);
        args.extend(["--a".into(), a.into(), "--b".into(), b.into(), "--names".into(), "A,B".into(), "--json".into()]);
        args.extend(shot.args());
        let out = self.run(&args).await?;
        serde_json::from_str(out.trim()).map_err(|e| Failed(format!("explain's report: {e}")))
    }

    /// Runs one child holding the GPU; its standard output when it compared or explained
    /// (exit 0, or 1: a failed comparison is a verdict), else its words.
    async fn run(&self, args: &[String]) -> Result<String, Failed> {
        let _gpu = self.gpu.lock().await;
        let mut command = Command::new(&self.twinray);
        command.args(args).args(&self.global).stdin(Stdio::null()).kill_on_drop(true);
        let started = command.output();
        let out = match tokio::time::timeout(self.backstop, started).await {
            Err(_) => {
                return Err(Failed(format!(
                    "twinray {} still ran after {} s and was stopped",
                    args[0],
                    self.backstop.as_secs()
                )))
            }
            Ok(Err(e)) => return Err(Failed(format!("starting {}: {e}", self.twinray.display()))),
            Ok(Ok(out)) => out,
        };
        match twinray_compile::exit_words(out.status) {
            None => Ok(String::from_utf8_lossy(&out.stdout).into_owned()),
            Some(words) => {
                let said = String::from_utf8_lossy(&out.stderr);
                let said = said.trim();
                Err(Failed(if said.is_empty() { words } else { format!("{said}\n{words}") }))
            }
        }
    }
}
