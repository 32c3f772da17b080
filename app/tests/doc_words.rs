//! No stale words in the docs (README.md, CONTRIBUTING.md and docs/*.md): every link and
//! anchor resolves, every repository path they name exists, every `twinray` command and flag
//! they name is in that command's `--help`, and every code block quoted from a stage's source
//! (`from=FILE`, or `from=FILE macro=NAME with="$a=>x|.."` for a macro's expansion) is still
//! what the source says. `cargo xtask` words are checked by xtask/tests/doc_words.rs.

use twinray_tests::docs as docs_text;
use twinray_tests::repo_root as root;

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::process::Command;

fn docs() -> Vec<(String, String)> {
    docs_text::docs(&root())
}

/// The inline code spans of `prose`.
fn spans(prose: &str) -> Vec<String> {
    prose.split('`').skip(1).step_by(2).map(str::to_string).collect()
}

/// GitHub's anchor for a heading: lowercase, punctuation dropped, spaces as hyphens.
fn slug(heading: &str) -> String {
    let text = heading.trim_start_matches('#').trim().to_lowercase();
    text.chars()
        .filter(|c| c.is_alphanumeric() || *c == ' ' || *c == '-' || *c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

fn anchors(markdown: &str) -> BTreeSet<String> {
    let (_, prose) = docs_text::fenced(markdown);
    prose.lines().filter(|l| l.starts_with('#')).map(slug).collect()
}

#[test]
fn every_link_and_anchor_resolves() {
    let mut broken = Vec::new();
    for (name, text) in docs() {
        let (_, prose) = docs_text::fenced(&text);
        let dir = root().join(&name).parent().unwrap().to_path_buf();
        for target in prose.split("](").skip(1).filter_map(|rest| rest.split(')').next()) {
            if target.starts_with("http://") || target.starts_with("https://") {
                continue;
            }
            let (file, anchor) = target.split_once('#').unwrap_or((target, ""));
            let path = if file.is_empty() { root().join(&name) } else { dir.join(file) };
            if !path.exists() {
                broken.push(format!("{name}: link to {target}: no such file"));
            } else if !anchor.is_empty() && !anchors(&std::fs::read_to_string(&path).unwrap()).contains(anchor) {
                broken.push(format!("{name}: link to {target}: no such heading"));
            }
        }
    }
    assert!(broken.is_empty(), "{}", broken.join("\n"));
}

/// Whether a code span names a path of this repository: it starts with one of its top-level
/// folders and holds no placeholder (`NAME`, `SET`, `*`, `...`).
fn repo_path(span: &str) -> Option<&str> {
    const TOP: &[&str] = &[
        "host/",
        "shaders-rs/",
        "shaders-glsl/",
        "docs/",
        "tests/",
        "xtask/",
        "scenes/",
        "probes/",
        "bench/",
        "spirv/",
        "fuzz/",
        ".ci/",
    ];
    let path = span.trim_end_matches([',', '.', ':']);
    let placeholder = path.chars().any(|c| c.is_ascii_uppercase() || "*<>{}$ ".contains(c)) || path.contains("...");
    (TOP.iter().any(|t| path.starts_with(t)) && !placeholder).then_some(path)
}

#[test]
fn every_path_the_docs_name_exists() {
    let mut missing = Vec::new();
    for (name, text) in docs() {
        let (_, prose) = docs_text::fenced(&text);
        for span in spans(&prose) {
            let Some(path) = repo_path(&span) else { continue };
            // The capsule is the example shape of the tutorial and of docs/adding-stages.md:
            // its files exist once you have followed them.
            let example = path.contains("capsule");
            if !example && !root().join(path).exists() && !ignored(path) {
                missing.push(format!("{name}: `{path}` does not exist"));
            }
        }
    }
    assert!(missing.is_empty(), "{}", missing.join("\n"));
}

/// Whether git ignores `path`: an output folder, such as the bench's default.
fn ignored(path: &str) -> bool {
    let out = Command::new("git").args(["check-ignore", "-q", path]).current_dir(root()).status();
    out.is_ok_and(|s| s.success())
}

fn help(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_twinray")).args(args).arg("--help").output().unwrap();
    assert!(out.status.success(), "twinray {args:?} --help: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// `twinray`'s subcommands, from its help.
fn commands(top: &str) -> BTreeSet<String> {
    let listed = top.split("Commands:\n").nth(1).unwrap_or("").split("\n\n").next().unwrap_or("");
    listed.lines().filter_map(|l| l.split_whitespace().next()).map(str::to_string).collect()
}

/// Each `twinray ...` invocation in `text`, a code block or span: a line that starts with
/// `twinray` (or runs it with `cargo run -p twinray --`), up to a shell separator (`|`, `;`,
/// `#`, `&&`).
fn invocations(text: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    for line in text.lines() {
        let line = line.trim_start().trim_start_matches("$ ");
        let Some(rest) = line.strip_prefix("twinray ").or_else(|| Some(line.split_once("-p twinray -- ")?.1)) else {
            continue;
        };
        let end = rest.find(['|', ';', '#']).unwrap_or(rest.len());
        let end = rest[..end].find("&&").unwrap_or(end);
        let words = rest[..end].split_whitespace().map(|w| w.trim_matches(['"', '\'', ',', ':']).to_string());
        out.push(words.collect());
    }
    out
}

/// `--flag` words of an invocation, without `=value`.
fn flags(words: &[String]) -> impl Iterator<Item = String> + '_ {
    let flag = |w: &&String| w.starts_with("--") && w[2..].starts_with(|c: char| c.is_ascii_lowercase());
    words.iter().filter(flag).map(|w| w.split(['=', '[']).next().unwrap_or(w).to_string())
}

#[test]
fn every_twinray_command_and_flag_the_docs_name_exists() {
    let top = help(&[]);
    let known = commands(&top);
    assert!(known.contains("compare") && known.contains("view"), "{top}");
    let mut helps = BTreeMap::new();
    let (mut stale, mut checked) = (Vec::new(), 0);
    for (name, text) in docs() {
        let (blocks, prose) = docs_text::fenced(&text);
        let code: Vec<String> = blocks.into_iter().map(|b| b.text).chain(spans(&prose)).collect();
        for words in code.iter().flat_map(|c| invocations(c)) {
            checked += 1;
            let command = words.iter().find(|w| known.contains(w.as_str()));
            if command.is_none()
                && words.first().is_some_and(|w| w.chars().all(|c| c.is_ascii_lowercase() || c == '-') && !w.is_empty())
            {
                stale.push(format!("{name}: `twinray {}`: no such command", words.join(" ")));
                continue;
            }
            // After a bare `--`, the arguments of the command `watch` runs: `compare`'s.
            let split = words.iter().position(|w| w == "--").unwrap_or(words.len());
            let (own, passed) = words.split_at(split);
            let mut parts = vec![(command.map(|c| c.as_str()), own)];
            if command.is_some_and(|c| c == "watch") {
                parts.push((Some("compare"), passed));
            }
            for (which, part) in parts {
                let args: Vec<&str> = which.into_iter().collect();
                let text = helps.entry(args.join(" ")).or_insert_with(|| help(&args));
                for flag in flags(part) {
                    if !text.contains(&format!("{flag} "))
                        && !text.contains(&format!("{flag}["))
                        && !text.contains(&format!("{flag}\n"))
                    {
                        stale.push(format!("{name}: `twinray {}`: {flag} is not in its --help", words.join(" ")));
                    }
                }
            }
        }
    }
    assert!(stale.is_empty(), "{}", stale.join("\n"));
    assert!(checked >= 50, "only {checked} twinray invocations found in the docs: is the scan still right?");
}

/// The text of `macro_rules! NAME`'s single arm in `source`, with `$(#[$doc])*` dropped and
/// each `$a=>x` of `with` (separated by `|`) substituted, longest first.
fn expansion(source: &str, name: &str, with: &str) -> String {
    let start = source.find(&format!("macro_rules! {name} {{")).unwrap_or_else(|| panic!("no macro {name}"));
    let body = start + source[start..].find("=> {\n").unwrap() + 5;
    let end = body + source[body..].find("\n    };\n}").unwrap();
    let mut text: String =
        source[body..end].lines().filter(|l| l.trim() != "$(#[$doc])*").collect::<Vec<_>>().join("\n");
    let mut pairs: Vec<(&str, &str)> = with.split('|').filter_map(|p| p.split_once("=>")).collect();
    pairs.sort_by_key(|(from, _)| std::cmp::Reverse(from.len()));
    for (from, to) in pairs {
        text = text.replace(from, to);
    }
    text
}

fn squeeze(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// `key=value` and `key="quoted value"` of an info string.
fn attribute(info: &str, key: &str) -> Option<String> {
    let rest = &info[info.find(&format!(" {key}="))? + key.len() + 2..];
    Some(match rest.strip_prefix('"') {
        Some(quoted) => quoted[..quoted.find('"')?].to_string(),
        None => rest.split_whitespace().next()?.to_string(),
    })
}

#[test]
fn code_quoted_from_the_source_is_what_the_source_says() {
    let mut checked = 0;
    for (name, text) in docs() {
        for docs_text::Block { info, text: block, line } in docs_text::fenced(&text).0 {
            let Some(file) = attribute(&info, "from") else { continue };
            let source = std::fs::read_to_string(root().join(&file)).unwrap_or_else(|e| panic!("{name}: {file}: {e}"));
            let want = match attribute(&info, "macro") {
                Some(mac) => squeeze(&expansion(&source, &mac, &attribute(&info, "with").unwrap_or_default())),
                None => squeeze(&block),
            };
            let found =
                if info.contains(" macro=") { squeeze(&block) == want } else { squeeze(&source).contains(&want) };
            assert!(found, "{name}:{line}: the ```{info} block is no longer what {file} says:\n{block}");
            checked += 1;
        }
    }
    assert!(checked >= 7, "only {checked} quoted blocks: docs/rust-stages.md shows a stage of each kind");
}

/// The repository explains itself: no tracked text file names a relative path (`../x`) that,
/// from the file's folder, leaves the repository (nor, in a Markdown file, one that does not
/// exist), nor a team note the repository does not hold (an upper-case Markdown file name
/// with no file of that name in it). Fuzz inputs and the hostile corpus, and code that tests
/// confinement, name escaping paths on purpose: only those leaving from the file's own folder
/// count, and the fuzz and hostile folders are not read.
#[test]
fn no_file_names_a_path_outside_the_repository() {
    let root = root();
    let listed = Command::new("git").args(["ls-files", "-z"]).current_dir(&root).output().unwrap();
    let files: Vec<String> =
        listed.stdout.split(|&b| b == 0).filter(|f| !f.is_empty()).map(|f| String::from_utf8_lossy(f).into()).collect();
    let names: BTreeSet<&str> = files.iter().filter_map(|f| f.rsplit('/').next()).collect();
    let mut out = Vec::new();
    for file in files.iter().filter(|f| !f.starts_with("fuzz/corpus/") && !f.starts_with("tests/hostile/")) {
        let Ok(text) = std::fs::read_to_string(root.join(file)) else { continue };
        let depth = file.matches('/').count();
        for (line, words) in text.lines().enumerate() {
            for word in words.split(|c: char| c.is_whitespace() || "`'\"()[]<>,;:=".contains(c)) {
                let path = word.trim_end_matches(['.', ')']);
                if path.starts_with("../") {
                    let ups = path.matches("../").count();
                    let folder = Path::new(file).parent().unwrap_or(Path::new(""));
                    let placeholder = path.contains(['*', '$', '{']) || path.contains("...");
                    if ups > depth {
                        out.push(format!("{file}:{}: `{path}` leaves the repository", line + 1));
                    } else if file.ends_with(".md") && !placeholder && !root.join(folder).join(path).exists() {
                        out.push(format!("{file}:{}: `{path}` does not exist", line + 1));
                    }
                }
                let name = path.rsplit('/').next().unwrap_or(path);
                let upper = name
                    .strip_suffix(".md")
                    .is_some_and(|n| !n.is_empty() && n.chars().all(|c| c.is_ascii_uppercase() || c == '_'));
                if upper && !names.contains(name) && !generated(name) {
                    out.push(format!("{file}:{}: `{path}` is not in the repository", line + 1));
                }
            }
        }
    }
    assert!(out.is_empty(), "{}", out.join("\n"));
}

/// Notes a command writes into its output folder (`bench/nvidia-run.sh` writes `COMMANDS.md`).
fn generated(note: &str) -> bool {
    note == "COMMANDS.md"
}

/// The module comment of `app/src/cli/main.rs` names every command `twinray --help` lists, so
/// a reader of the code finds each command's module from there.
#[test]
fn the_command_module_comment_names_every_command() {
    let main = std::fs::read_to_string(root().join("app/src/cli/main.rs")).unwrap();
    let comment: String = main.lines().take_while(|l| l.starts_with("//!")).collect::<Vec<_>>().join("\n");
    let missing: Vec<String> =
        commands(&help(&[])).into_iter().filter(|c| c != "help" && !comment.contains(&format!("`{c}`"))).collect();
    assert!(missing.is_empty(), "app/src/cli/main.rs's module comment does not name: {missing:?}");
}

/// docs/architecture.md is a code map a reader can hold: no line over 100 characters, and every
/// folder the repository tracks at its top level (and each crate's folder) named in it.
#[test]
fn the_code_map_names_every_folder_in_short_lines() {
    let doc = std::fs::read_to_string(root().join("docs/architecture.md")).unwrap();
    let long: Vec<usize> =
        doc.lines().enumerate().filter(|(_, l)| l.chars().count() > 100).map(|(i, _)| i + 1).collect();
    assert!(long.is_empty(), "docs/architecture.md: lines over 100 characters: {long:?}");
    let listed =
        Command::new("git").args(["ls-tree", "-d", "--name-only", "HEAD"]).current_dir(root()).output().unwrap();
    let mut folders: Vec<String> = String::from_utf8_lossy(&listed.stdout).lines().map(|f| format!("{f}/")).collect();
    folders.extend(
        ["app/src/cli/", "app/tests/", "shaders-rs/shared/", "shaders-rs/stages/", "shaders-rs/compile/"]
            .map(String::from),
    );
    let missing: Vec<&String> = folders.iter().filter(|f| !doc.contains(f.trim_start_matches("host/"))).collect();
    assert!(missing.is_empty(), "docs/architecture.md does not name: {missing:?}");
}
