//! `twinray stability`: the hard-case suite, every case of a folder per set and formula.

use crate::args::{GlobalArgs, MAX_RUNS, MAX_TIMING_RAYS, MAX_WARMUP};
use crate::session::context;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray_host::probe::case::ProbeCase;
use twinray_host::scene::shape::Formula;

pub fn stability(global: &GlobalArgs, args: StabilityArgs) -> Result<ExitCode> {
    let specs = args.sets.split(';').map(str::parse).collect::<Result<Vec<twinray_host::sets::SetSpec>, _>>()?;
    let sets = global.load_all("--sets", &specs)?;
    if args.against_world {
        return against_world(global, &args, &sets);
    }
    let files = twinray_host::probe::stability::case_files(&args.dir)?;
    let ctx = context(global)?;
    let formulas = [Formula::Robust, Formula::Naive];
    let timing = twinray_host::probe::stability::Timing {
        warmup: args.warmup,
        runs: args.runs,
        rays: args.timing_rays as usize,
    };
    // Each skip is said as it happens, on stderr, so JSON on stdout stays the rows.
    let skip = |s: &twinray_host::probe::stability::Skipped| eprintln!("{}", s.line());
    let suite = twinray_host::probe::stability::run(&ctx, &files, &sets, &formulas, timing, skip)?;
    let rows = &suite.rows;
    if args.json {
        println!("{}", serde_json::to_string(rows)?);
    } else {
        print!("{}", twinray_host::probe::stability::table(rows));
    }
    if !suite.skipped.is_empty() {
        let names: Vec<&str> = suite.skipped.iter().map(|s| s.name.as_str()).collect();
        let line = format!(
            "skipped {} of {} cases, which need what {} lacks: {}",
            names.len(),
            files.len(),
            ctx.info.name,
            names.join(", ")
        );
        if args.json {
            eprintln!("{line}")
        } else {
            println!("{line}")
        }
    }
    let missed = rows.iter().filter(|r| !r.failures.is_empty()).count();
    Ok(if missed == 0 { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

/// `--against-world`: every case (of the folder, or random) with every set, at its chosen
/// origins and at world coordinates.
fn against_world(global: &GlobalArgs, args: &StabilityArgs, sets: &[twinray_host::ShaderSet]) -> Result<ExitCode> {
    let sources: Vec<Source> = match args.random {
        Some(n) => (args.seed..args.seed.saturating_add(n)).map(Source::Random).collect(),
        None => twinray_host::probe::stability::case_files(&args.dir)?.into_iter().map(Source::File).collect(),
    };
    let ctx = context(global)?;
    let mut checks = Vec::new();
    for (done, source) in sources.iter().enumerate() {
        let case = source.load(args.write_cases.as_deref())?;
        for set in sets {
            match twinray_host::probe::origins::check(&ctx, &case, set) {
                Ok(check) => checks.push(check),
                Err(e) if e.device_lacks() => eprintln!("skipped {}: {e}", case.file.name),
                Err(e) => return Err(e.into()),
            }
        }
        twinray_host::util::progress::report("cases", done as u64 + 1, sources.len() as u64);
    }
    if args.json {
        println!("{}", serde_json::to_string(&checks)?);
    } else {
        print!("{}", twinray_host::probe::origins::table(&checks));
    }
    let worse = checks.iter().filter(|c| !c.failures.is_empty()).count();
    if !args.json {
        println!("{worse} of {} rows worse at the chosen origins than at world coordinates", checks.len());
    }
    Ok(if worse == 0 { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

/// Where a case of `--against-world` comes from.
enum Source {
    File(PathBuf),
    /// A random case's seed (`twinray_host::probe::random`).
    Random(u64),
}

impl Source {
    /// The case, its file first written to `write_to` where a random one is asked to be.
    fn load(&self, write_to: Option<&std::path::Path>) -> Result<ProbeCase> {
        Ok(match self {
            Source::File(path) => twinray_host::probe::builtin::open(path, &[])?,
            Source::Random(seed) => {
                let text = twinray_host::probe::random::origin_case(*seed);
                if let Some(dir) = write_to {
                    twinray_host::util::output::write_atomically(
                        &dir.join(format!("random-{seed}.toml")),
                        text.as_bytes(),
                    )?;
                }
                ProbeCase::parse(&text, &format!("random case {seed}"), std::env::temp_dir())?
            }
        })
    }
}

#[derive(Args)]
pub struct StabilityArgs {
    /// Folder of probe cases.
    #[arg(long, default_value = "probes/stability")]
    pub dir: PathBuf,
    /// Shader sets, comma-separated with ';' between sets, e.g. "rust;glsl".
    #[arg(long, default_value = "rust;glsl")]
    pub sets: String,
    /// Timed passes per case, set and formula.
    #[arg(long, default_value_t = 5, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_RUNS)))]
    pub runs: u32,
    /// Untimed passes before the timed ones.
    #[arg(long, default_value_t = 1, allow_negative_numbers = true, value_parser = clap::value_parser!(u32).range(0..=i64::from(MAX_WARMUP)))]
    pub warmup: u32,
    /// Time each case over its rays repeated up to at least this many (0: the case's rays).
    #[arg(long, default_value_t = 262_144, value_parser = clap::value_parser!(u64).range(0..=MAX_TIMING_RAYS))]
    pub timing_rays: u64,
    /// Print one JSON array of rows.
    #[arg(long)]
    pub json: bool,
    /// Instead of the suite: probe every case (robust formulas) at the origins twinray chooses
    /// and at world coordinates, and fail where the chosen origins make a ray wrong that world
    /// coordinates get right, or make the relative t error's p99 grow (docs/numerics.md).
    #[arg(long)]
    pub against_world: bool,
    /// With --against-world: N random cases of far-apart ray groups in place of the folder's
    /// (the property test's generator, `twinray_host::probe::random`).
    #[arg(long, value_name = "N", requires = "against_world", value_parser = clap::value_parser!(u64).range(1..=100_000))]
    pub random: Option<u64>,
    /// With --random: the first case's seed; case k is seed + k.
    #[arg(long, default_value_t = 0, requires = "random")]
    pub seed: u64,
    /// With --random: write each case's file to DIR (random-SEED.toml), to probe it again.
    #[arg(long, value_name = "DIR", requires = "random")]
    pub write_cases: Option<PathBuf>,
}
