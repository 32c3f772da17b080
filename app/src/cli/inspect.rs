//! `twinray inspect`: what each stage of a set keeps alive across each trace and callable
//! call, beside the stack size the driver gives it; or two sets side by side.

use crate::args::GlobalArgs;
use crate::session::context;
use anyhow::{bail, Context as _, Result};
use clap::Args;
use serde::Serialize;
use std::path::PathBuf;
use std::process::ExitCode;
use twinray_host::render::stacks::{inspected, stage_stacks};
use twinray_host::sets::inspect::{self, Entry, Site};
use twinray_host::sets::{ShaderSet, Stage, MODULES};

#[derive(Args)]
pub struct InspectArgs {
    /// The shader set (`rust`, `glsl`, a folder of modules, a mix such as
    /// `glsl,raygen=my_raygen.spv`), or one SPIR-V file, whose every entry point is analysed.
    #[arg(conflicts_with_all = ["a", "b"], required_unless_present = "a")]
    pub set: Option<String>,
    /// Two sets side by side, stage by stage: this one...
    #[arg(long, requires = "b")]
    pub a: Option<String>,
    /// ...and this one.
    #[arg(long, requires = "a")]
    pub b: Option<String>,
    /// Only this module (`raygen`, `triangle_closest_hit_callable`, ...), or every module of
    /// this stage (`closest_hit`, `miss`, ...).
    #[arg(long, value_name = "NAME")]
    pub stage: Option<String>,
    /// Print one JSON object: every call site with each value live across it.
    #[arg(long)]
    pub json: bool,
    /// List every value live across each call, not only their count and bytes.
    #[arg(long)]
    pub values: bool,
    /// Analyse each module as it is, without first specialising it, inlining its functions and
    /// turning its local variables into SSA values (spirv-opt), as a driver would.
    #[arg(long)]
    pub raw: bool,
    /// Leave out the driver's stack sizes (then no Vulkan device is needed).
    #[arg(long)]
    pub no_stacks: bool,
    /// Samples per pixel ray generation is specialised for, in the analysis and when the driver
    /// sizes its stack: a square.
    #[arg(long, default_value_t = 16)]
    pub spp: u32,
    /// The scene features every stage is specialised for, in the analysis and when the driver
    /// compiles it: `all`, `none`, or names such as `textures,emission`
    /// (`twinray_shared::features`); a scene without them runs the stages as specialised for
    /// `none`.
    #[arg(long, default_value = "all", value_parser = |t: &str| twinray_shared::features::bits_named(t))]
    pub features: u32,
}

/// One module of a set: its calls, and its stack.
#[derive(Serialize)]
struct ModuleReport {
    module: String,
    stage: String,
    /// Bytes, where the driver gave a figure.
    stack: Option<u64>,
    /// Why there is none.
    #[serde(skip_serializing_if = "Option::is_none")]
    no_stack: Option<String>,
    entries: Vec<Entry>,
}

impl ModuleReport {
    fn sites(&self) -> impl Iterator<Item = &Site> {
        self.entries.iter().flat_map(|e| e.sites.iter())
    }

    fn max_bytes(&self) -> u64 {
        self.entries.iter().map(Entry::max_bytes).max().unwrap_or(0)
    }
}

#[derive(Serialize)]
struct SetReport {
    set: String,
    normalised: bool,
    modules: Vec<ModuleReport>,
}

pub fn inspect(global: &GlobalArgs, args: InspectArgs) -> Result<ExitCode> {
    let side = (args.spp as f64).sqrt().round() as u32;
    if side == 0 || side * side != args.spp {
        bail!(twinray_host::Error::Input(format!("--spp {} is not a square", args.spp)));
    }
    let texts: Vec<&String> = [&args.set, &args.a, &args.b].into_iter().flatten().collect();
    let reports = texts.iter().map(|t| report(global, t, &args, side)).collect::<Result<Vec<SetReport>>>()?;
    if args.json {
        let value = match reports.as_slice() {
            [one] => serde_json::to_value(one)?,
            _ => serde_json::json!({ "a": reports[0], "b": reports[1] }),
        };
        println!("{}", serde_json::to_string_pretty(&value)?);
    } else if let [a, b] = reports.as_slice() {
        print!("{}", side_by_side(a, b));
    } else {
        print!("{}", describe(&reports[0], args.values));
    }
    Ok(ExitCode::SUCCESS)
}

/// The report of one set (or one file).
fn report(global: &GlobalArgs, text: &str, args: &InspectArgs, side: u32) -> Result<SetReport> {
    let spec = inspected(side, args.features).pairs();
    let analyse = |bytes: &[u8]| -> Result<Vec<Entry>> {
        let module = if args.raw {
            bytes.to_vec()
        } else {
            inspect::normalise(bytes, &spec).map_err(twinray_host::Error::Input)?
        };
        Ok(inspect::inspect(&module).map_err(twinray_host::Error::Input)?)
    };
    let file = PathBuf::from(text);
    if file.is_file() {
        let bytes = std::fs::read(&file).with_context(|| format!("reading {}", file.display()))?;
        let entries = analyse(&bytes).with_context(|| file.display().to_string())?;
        let module = ModuleReport {
            module: file.display().to_string(),
            stage: entries.iter().map(|e| e.model.clone()).collect::<Vec<_>>().join(", "),
            stack: None,
            no_stack: Some("a file on its own: inspect a set that holds it for the driver's figure".into()),
            entries,
        };
        return Ok(SetReport { set: text.to_string(), normalised: !args.raw, modules: vec![module] });
    }
    let set: ShaderSet = global.load("the set", &text.parse()?)?;
    let names = chosen(&set, args.stage.as_deref())?;
    let stacks = if args.no_stacks {
        Vec::new()
    } else {
        let ctx = context(global)?;
        stage_stacks(&ctx, &set, &names, (side, args.features)).context("sizing the stages' stacks")?
    };
    let mut modules = Vec::new();
    for name in names {
        let m = set.module(name)?;
        let entries = analyse(&m.spirv).with_context(|| format!("{set}: {name}"))?;
        let stack = stacks.iter().find(|(n, _)| n == name).map(|(_, s)| s.clone());
        let (stack, no_stack) = match stack {
            Some(Ok(bytes)) => (Some(bytes), None),
            Some(Err(why)) => (None, Some(why)),
            None if args.no_stacks => (None, Some("--no-stacks".into())),
            None => (None, Some("not sized".into())),
        };
        modules.push(ModuleReport { module: name.into(), stage: m.spec.stage.name().into(), stack, no_stack, entries });
    }
    Ok(SetReport { set: set.to_string(), normalised: !args.raw, modules })
}

/// The modules `--stage` names (a module, or a stage's modules), of those the set has.
fn chosen(set: &ShaderSet, stage: Option<&str>) -> Result<Vec<&'static str>> {
    let stage_of = |s: &str| Stage::ALL.into_iter().find(|k| k.name() == s);
    let names: Vec<&'static str> = match stage {
        None => MODULES.iter().map(|m| m.name).collect(),
        Some(n) if MODULES.iter().any(|m| m.name == n) => {
            MODULES.iter().filter(|m| m.name == n).map(|m| m.name).collect()
        }
        Some(n) => match stage_of(n) {
            Some(k) => MODULES.iter().filter(|m| m.stage == k).map(|m| m.name).collect(),
            None => {
                let stages: Vec<&str> = Stage::ALL.iter().map(|s| s.name()).collect();
                bail!(twinray_host::Error::Input(format!(
                    "--stage {n}: no module or stage of that name (stages: {})",
                    stages.join(", ")
                )))
            }
        },
    };
    Ok(names.into_iter().filter(|n| !set.lacks(n)).collect())
}

fn stack_text(m: &ModuleReport) -> String {
    match (m.stack, &m.no_stack) {
        (Some(bytes), _) => format!("stack {bytes} B"),
        (None, Some(why)) => format!("no stack figure: {why}"),
        (None, None) => "no stack figure".into(),
    }
}

/// One set, module by module.
fn describe(report: &SetReport, values: bool) -> String {
    let how = if report.normalised { "normalised by spirv-opt as a driver would" } else { "as written (--raw)" };
    let mut out = format!("{} ({how})\n", report.set);
    let mut quiet = Vec::new();
    for m in &report.modules {
        if m.sites().next().is_none() {
            quiet.push(m.module.as_str());
            continue;
        }
        out += &format!("\n{} ({}), {}\n", m.module, m.stage, stack_text(m));
        for e in &m.entries {
            for s in &e.sites {
                out += &site_text(s, values);
            }
        }
    }
    if !quiet.is_empty() {
        out += &format!("\nno trace or callable call: {}\n", quiet.join(", "));
    }
    out
}

fn site_text(s: &Site, values: bool) -> String {
    let variables = s.live.iter().filter(|l| l.kind == "variable").count();
    let mut out = format!(
        "  {} at {} (in {}): {} B live across it, {} values and {} variables\n",
        s.call,
        s.at,
        s.path.join(" > "),
        s.bytes,
        s.live.len() - variables,
        variables
    );
    if !s.loops.is_empty() {
        let loops: Vec<String> =
            s.loops.iter().map(|l| format!("%{} carries {} ({} B)", l.header, l.carried, l.carried_bytes)).collect();
        out += &format!("    in loops {}\n", loops.join(" > "));
    }
    if values {
        for l in &s.live {
            let origin = l.origin.as_deref().map(|o| format!("  {o}")).unwrap_or_default();
            out += &format!("    {:>4} B  {:<8} %{:<6} {:<16} {}{origin}\n", l.bytes, l.kind, l.id, l.made_by, l.ty);
        }
    }
    out
}

/// Two sets, module by module: stack and the bytes live across each call.
fn side_by_side(a: &SetReport, b: &SetReport) -> String {
    let mut out = format!("A = {}\nB = {}\n\n", a.set, b.set);
    out +=
        &format!("{:<34} {:>8} {:>8}  {:<24} {:<24}\n", "module", "stack A", "stack B", "live bytes per call, A", "B");
    let bytes = |m: Option<&ModuleReport>| -> String {
        m.map(|m| m.sites().map(|s| s.bytes.to_string()).collect::<Vec<_>>().join(" ")).unwrap_or_default()
    };
    let stack = |m: Option<&ModuleReport>| m.and_then(|m| m.stack).map_or("-".into(), |s| s.to_string());
    for ma in &a.modules {
        let mb = b.modules.iter().find(|m| m.module == ma.module);
        if ma.sites().next().is_none() && mb.is_none_or(|m| m.sites().next().is_none()) {
            continue;
        }
        let more = match mb {
            Some(mb) if ma.max_bytes() > mb.max_bytes() => "  A keeps more",
            Some(mb) if ma.max_bytes() < mb.max_bytes() => "  B keeps more",
            _ => "",
        };
        out += &format!(
            "{:<34} {:>8} {:>8}  {:<24} {:<24}{more}\n",
            ma.module,
            stack(Some(ma)),
            stack(mb),
            bytes(Some(ma)),
            bytes(mb)
        );
    }
    out
}
