//! The fuzz campaign (`kind = "robustness_fuzz"`): scenes mutated from the examples the way a
//! careless or hostile user would ([`mutation`]) run through `verify scene`, each bounded in
//! time (a thread-local time limit, [`contactlab::run_control::with_time_limit`]) and memory (the
//! scene's own estimate against a limit), each outcome classified:
//!
//! - `ran`: a solution, every written JSON number finite (no `null` where a number belongs) and
//!   no NaN or ∞ in a plot;
//! - `error`: a typed error (the message is kept; whether it names the mutated key is counted);
//! - `stopped`: the time limit stopped the run at a step it names (a long scene, not a hang);
//! - `panic`, `hang` (no answer within the limit plus a grace period) and `non_finite` (a number
//!   that is not finite in a written output): defects, gated at zero.
//!
//! An allocation the estimates miss aborts the process: the campaign then does not finish, which
//! fails the run as surely as a gate.
//!
//! Imports: core and the scene runner passed in by the registry (no family).

pub mod mutation;
pub mod outputs;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

use serde::Deserialize;

use contactlab::run_control::StopTiming;

use crate::core::case::Case;
use crate::core::format::{invalid, positive, CaseError};
use crate::core::gate::{Check, GateVerdict};
use crate::core::report::case_report::{CaseReport, Table};
use mutation::{get_mut, mutate, parse_path, Rng};

/// The case kinds of the campaign.
pub const KINDS: [&str; 1] = ["robustness_fuzz"];

/// `verify scene`'s runner: the scene file and the output directory, to a summary or an error.
pub type SceneRunner = fn(&Path, &Path) -> Result<String, String>;

/// A base scene: an example, shrunk by `set` so that one run costs milliseconds.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Base {
    /// The model group it counts under (`rod`, `plane`, `dynamic`, `moving`).
    pub model: String,
    /// The example scene, relative to the case file.
    pub scene: PathBuf,
    /// Values replaced before mutating (`"time.steps" = 20`, `"sweep[0].points" = 5`).
    #[serde(default)]
    pub set: toml::Table,
}

/// The campaign's format.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FuzzCase {
    /// The campaign's seed: scene i of base b is reproduced from (seed, b, i).
    pub seed: u64,
    /// Mutated scenes per model group (split evenly over its bases).
    pub scenes_per_model: usize,
    /// Each scene's own time limit (s).
    pub time_limit: f64,
    /// Beyond the time limit, how long a scene may take to answer before it counts as a hang (s).
    pub hang_grace: f64,
    /// The memory a scene may claim (bytes, with K, M, G).
    pub max_memory: String,
    /// Scenes run at once.
    #[serde(default = "default_lanes")]
    pub lanes: usize,
    /// The least share of each model's errors that must name the mutated key (gated only when
    /// given: a campaign of 10⁴ scenes per model measures it to ±0.5 %; one of 100 does not).
    #[serde(default)]
    pub min_naming_share: Option<f64>,
    pub base: Vec<Base>,
}

fn default_lanes() -> usize {
    2
}

impl FuzzCase {
    pub fn check(&self, path: &Path) -> Result<(), CaseError> {
        positive(path, "time_limit", self.time_limit)?;
        positive(path, "hang_grace", self.hang_grace)?;
        if contactlab::scene::memory::parse_size(&self.max_memory).is_none() {
            return Err(invalid(
                path,
                "max_memory",
                &self.max_memory,
                "a size such as 1G",
            ));
        }
        if self.scenes_per_model == 0 || self.base.is_empty() || self.lanes == 0 {
            return Err(invalid(
                path,
                "scenes_per_model / base / lanes",
                self.scenes_per_model,
                "at least one scene, one base and one lane",
            ));
        }
        Ok(())
    }
}

/// Scenes of each base shown in the examples table.
const EXAMPLES_PER_BASE: usize = 2;

/// The outcome of one scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Outcome {
    Ran,
    Error,
    Stopped,
    Panic,
    Hang,
    NonFinite,
    /// The time limit stopped the run but its error says something else (a stop wrapped into
    /// an input error, or lost).
    MisreportedStop,
}

impl Outcome {
    const ALL: [Outcome; 7] = [
        Outcome::Ran,
        Outcome::Error,
        Outcome::Stopped,
        Outcome::Panic,
        Outcome::Hang,
        Outcome::NonFinite,
        Outcome::MisreportedStop,
    ];

    fn name(self) -> &'static str {
        match self {
            Outcome::Ran => "ran",
            Outcome::Error => "error",
            Outcome::Stopped => "stopped",
            Outcome::Panic => "panic",
            Outcome::Hang => "hang",
            Outcome::NonFinite => "non_finite",
            Outcome::MisreportedStop => "misreported_stop",
        }
    }

    /// Panic, hang, non-finite output or a stop reported as something else.
    pub fn is_defect(self) -> bool {
        matches!(
            self,
            Outcome::Panic | Outcome::Hang | Outcome::NonFinite | Outcome::MisreportedStop
        )
    }
}

/// One scene's result.
#[derive(Debug, Clone)]
struct SceneResult {
    model: String,
    base: usize,
    index: usize,
    mutations: String,
    /// The mutated keys' last components (what an error should name).
    keys: Vec<String>,
    outcome: Outcome,
    message: String,
    /// For a stopped scene: what the time limit's clock measured.
    stop: Option<StopTiming>,
}

/// A mutated scene: its text, the files it refers to by a relative name (a mutated mesh,
/// written beside it), the mutated keys' last components (what an error should name) and a
/// description of the mutations.
pub struct MutatedScene {
    pub text: String,
    pub files: Vec<(String, Vec<u8>)>,
    pub keys: Vec<String>,
    pub what: String,
}

/// The name a mutated mesh file is written under, beside the scene (and what an error about it
/// should name: the file as the scene names it).
pub const MUTATED_MESH: &str = "mutated.msh";

/// A scene of the campaign: the base with its shrink values, mutated; now and then its mesh file
/// mutated too ([`mutation::mutate_file`]: a copy written beside the scene, the scene pointed at
/// it), and its ParaView series asked for (`output.vtk = true` where the scene has an
/// `[output]`), so that the non-finite scan reads the `.vtu` files as well.
pub fn scene_text(base: &toml::Table, seed: u64, b: usize, index: usize) -> MutatedScene {
    let mut doc = toml::Value::Table(base.clone());
    let mut rng = Rng::for_scene(seed, b, index);
    let mut mutations = mutate(&mut doc, &mut rng);
    let mut keys: Vec<String> = mutations
        .iter()
        .map(|m| {
            m.key
                .rsplit('.')
                .next()
                .unwrap_or(&m.key)
                .split('[')
                .next()
                .unwrap_or("")
                .to_string()
        })
        .collect();
    let mut files = Vec::new();
    if rng.below(4) == 0 {
        if let Some((m, bytes)) = mutate_mesh_file(&mut doc, &mut rng) {
            mutations.push(m);
            keys.push(MUTATED_MESH.into());
            files.push((MUTATED_MESH.to_string(), bytes));
        }
    }
    if rng.below(4) == 0 {
        if let Some(toml::Value::Table(out)) = doc.get_mut("output") {
            out.insert("vtk".into(), toml::Value::Boolean(true));
        }
    }
    let what = mutations
        .iter()
        .map(|m| m.describe())
        .collect::<Vec<_>>()
        .join("; ");
    let text = match &doc {
        toml::Value::Table(t) => toml::to_string(t).unwrap_or_default(),
        _ => String::new(),
    };
    MutatedScene {
        text,
        files,
        keys,
        what,
    }
}

/// Every `file = "…"` of `v` (absolute after [`shrunk`]), by path.
fn file_keys(v: &toml::Value, path: &mut Vec<mutation::Step>, out: &mut Vec<Vec<mutation::Step>>) {
    match v {
        toml::Value::Table(t) => {
            for (k, x) in t {
                path.push(mutation::Step::Key(k.clone()));
                if k == "file" && x.is_str() {
                    out.push(path.clone());
                } else {
                    file_keys(x, path, out);
                }
                path.pop();
            }
        }
        toml::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                path.push(mutation::Step::Index(i));
                file_keys(x, path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

/// One of the scene's mesh files read, mutated and named [`MUTATED_MESH`] in the scene; None
/// when the scene names no file (or it cannot be read: the scene then keeps its own).
fn mutate_mesh_file(doc: &mut toml::Value, rng: &mut Rng) -> Option<(mutation::Mutation, Vec<u8>)> {
    let mut paths = Vec::new();
    file_keys(doc, &mut Vec::new(), &mut paths);
    if paths.is_empty() {
        return None;
    }
    let path = paths[rng.below(paths.len())].clone();
    let slot = get_mut(doc, &path)?;
    let bytes = std::fs::read(slot.as_str()?).ok()?;
    let (mutated, what) = mutation::mutate_file(&bytes, rng);
    *slot = toml::Value::String(MUTATED_MESH.into());
    Some((
        mutation::Mutation {
            key: mutation::path_text(&path),
            what: format!("its mesh {what}"),
        },
        mutated,
    ))
}

/// The base scene with its shrink values applied.
pub fn shrunk(case_dir: &Path, base: &Base) -> Result<toml::Table, String> {
    let path = case_dir.join(&base.scene);
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut doc = toml::Value::Table(
        text.parse::<toml::Table>()
            .map_err(|e| format!("{}: {e}", path.display()))?,
    );
    for (key, value) in &base.set {
        let steps = parse_path(key);
        let slot = get_mut(&mut doc, &steps)
            .ok_or_else(|| format!("{}: set.{key}: no such key in the scene", path.display()))?;
        *slot = value.clone();
    }
    // a mesh file named relative to the example is named from anywhere (the mutated scene is
    // written elsewhere)
    if let Some(dir) = path.parent() {
        absolute_files(&mut doc, dir);
    }
    match doc {
        toml::Value::Table(t) => Ok(t),
        _ => Err(format!("{}: not a table", path.display())),
    }
}

/// Every `file = "relative/path"` in `v` made relative to `dir` instead.
fn absolute_files(v: &mut toml::Value, dir: &Path) {
    match v {
        toml::Value::Table(t) => {
            for (key, value) in t.iter_mut() {
                match value {
                    toml::Value::String(f)
                        if key == "file" && Path::new(f.as_str()).is_relative() =>
                    {
                        *f = dir.join(f.as_str()).display().to_string();
                    }
                    _ => absolute_files(value, dir),
                }
            }
        }
        toml::Value::Array(a) => a.iter_mut().for_each(|x| absolute_files(x, dir)),
        _ => {}
    }
}

/// What one scene's thread answered: the runner's result, whether it panicked, and what the time
/// limit's clock measured.
type Answer = (Result<String, String>, bool, StopTiming);

/// Runs one scene in its own thread with its time limit; `None` when it did not answer in time.
fn run_one(
    runner: SceneRunner,
    dir: &Path,
    text: String,
    files: &[(String, Vec<u8>)],
    limit: Duration,
    grace: Duration,
) -> Option<Answer> {
    let unmeasured = StopTiming {
        checks_before: 0,
        longest_step_before: Duration::ZERO,
        fired_after_limit: None,
        fired_checks: 0,
        threads: 0,
    };
    let _ = std::fs::remove_dir_all(dir);
    if std::fs::create_dir_all(dir).is_err() {
        return Some((
            Err("cannot create the scene directory".into()),
            false,
            unmeasured,
        ));
    }
    let file = dir.join("scene.toml");
    if std::fs::write(&file, text).is_err() {
        return Some((Err("cannot write the scene".into()), false, unmeasured));
    }
    for (name, bytes) in files {
        if std::fs::write(dir.join(name), bytes).is_err() {
            return Some((Err(format!("cannot write {name}")), false, unmeasured));
        }
    }
    let out = dir.join("out");
    let (tx, rx) = mpsc::channel();
    let spawned = std::thread::Builder::new().spawn(move || {
        let deadline = contactlab::run_control::Deadline::from_now(limit);
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            contactlab::run_control::with_deadline(Some(deadline.clone()), || runner(&file, &out))
        }));
        let timing = deadline.timing();
        let _ = tx.send(match result {
            Ok(r) => (r, false, timing),
            Err(p) => (
                Err(p
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default()),
                true,
                timing,
            ),
        });
    });
    if spawned.is_err() {
        return Some((Err("cannot spawn a thread".into()), false, unmeasured));
    }
    rx.recv_timeout(limit + grace).ok()
}

/// Runs one scene (TOML `text`) in `dir` with its time limit and classifies the outcome; the
/// message is the summary, the error, or where a non-finite number was written. Whatever the
/// outcome, every file the run wrote is scanned (a run that ends in an error or a stop writes
/// what it computed until then). A stop comes with what the clock measured.
pub fn classify_timed(
    runner: SceneRunner,
    dir: &Path,
    scene: &MutatedScene,
    limit: Duration,
    grace: Duration,
) -> (Outcome, String, Option<StopTiming>) {
    let answer = run_one(runner, dir, scene.text.clone(), &scene.files, limit, grace);
    let Some((result, panicked, timing)) = answer else {
        return (Outcome::Hang, String::new(), None);
    };
    if panicked {
        return (Outcome::Panic, result.err().unwrap_or_default(), None);
    }
    if let Some(where_) = outputs::first_non_finite(&dir.join("out")) {
        return (Outcome::NonFinite, where_, None);
    }
    match result {
        Ok(summary) => (Outcome::Ran, summary, None),
        Err(e) if e.contains("the time limit of") => (Outcome::Stopped, e, Some(timing)),
        Err(e) if timing.fired_after_limit.is_some() => (Outcome::MisreportedStop, e, None),
        Err(e) => (Outcome::Error, e, None),
    }
}

/// [`classify_timed`] without the clock.
pub fn classify(
    runner: SceneRunner,
    dir: &Path,
    scene: &MutatedScene,
    limit: Duration,
    grace: Duration,
) -> (Outcome, String) {
    let (o, m, _) = classify_timed(runner, dir, scene, limit, grace);
    (o, m)
}

/// Runs the campaign and fills the report.
pub fn run(
    case: &Case,
    c: &FuzzCase,
    runner: SceneRunner,
    report: &mut CaseReport,
) -> Result<(), String> {
    let case_dir = case
        .path()
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let bases: Vec<toml::Table> = c
        .base
        .iter()
        .map(|b| shrunk(&case_dir, b))
        .collect::<Result<_, _>>()?;
    // scenes per base: the model's share split evenly over its bases
    let mut per_model: BTreeMap<&str, usize> = BTreeMap::new();
    for b in &c.base {
        *per_model.entry(b.model.as_str()).or_default() += 1;
    }
    let mut work: Vec<(usize, usize)> = Vec::new();
    for (bi, b) in c.base.iter().enumerate() {
        let n_bases = per_model[b.model.as_str()];
        let share = c.scenes_per_model.div_ceil(n_bases);
        work.extend((0..share).map(|i| (bi, i)));
    }
    let limit = Duration::from_secs_f64(c.time_limit);
    let grace = Duration::from_secs_f64(c.hang_grace);
    let bytes = contactlab::scene::memory::parse_size(&c.max_memory).unwrap_or(1 << 30);
    let previous_limit = match contactlab::scene::memory::memory_limit() {
        (b, "--max-memory") => b,
        _ => 0,
    };
    contactlab::scene::memory::set_memory_limit(bytes);
    let root = std::env::temp_dir().join(format!("contactlab-fuzz-{}", std::process::id()));
    // every base must run as it is: a base that fails would make its mutations say little
    let mut base_rows = Vec::new();
    let mut base_checks = Vec::new();
    for (b, table) in c.base.iter().zip(&bases) {
        let text = toml::to_string(table).unwrap_or_default();
        let answer = run_one(runner, &root.join("base"), text, &[], limit, grace);
        let (ran, message) = match answer {
            Some((Ok(summary), false, _)) => {
                match outputs::first_non_finite(&root.join("base/out")) {
                    None => (true, summary),
                    Some(w) => (false, w),
                }
            }
            Some((Err(e), _, _)) => (false, e),
            Some((Ok(_), true, _)) => (false, "panicked".into()),
            None => (false, "no answer".into()),
        };
        base_checks.push(Check::holds(
            &format!("{} runs unmutated", b.scene.display()),
            ran,
            "a solution with finite outputs",
        ));
        if !ran {
            base_rows.push(vec![b.scene.display().to_string(), message]);
        }
    }
    report.gates.push(GateVerdict::from_checks(
        "fuzz: every base scene runs unmutated".into(),
        "extreme",
        base_checks,
        "the bases are the examples with their sizes shrunk (`set`)",
    ));
    if !base_rows.is_empty() {
        report.tables.push(Table {
            title: "base scenes that do not run".into(),
            header: vec!["base".into(), "message".into()],
            rows: base_rows,
        });
    }
    let next = std::sync::atomic::AtomicUsize::new(0);
    let mut results: Vec<SceneResult> = Vec::with_capacity(work.len());
    std::thread::scope(|scope| {
        let lanes: Vec<_> = (0..c.lanes)
            .map(|lane| {
                let (work, bases, next, root) = (&work, &bases, &next, &root);
                scope.spawn(move || {
                    let mut dir = root.join(format!("lane-{lane}"));
                    let mut hangs = 0usize;
                    let mut mine = Vec::new();
                    loop {
                        let w = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        let Some(&(b, index)) = work.get(w) else {
                            break;
                        };
                        let scene = scene_text(&bases[b], c.seed, b, index);
                        let (outcome, message, stop) =
                            classify_timed(runner, &dir, &scene, limit, grace);
                        let (keys, mutations) = (scene.keys, scene.what);
                        mine.push((
                            w,
                            SceneResult {
                                model: c.base[b].model.clone(),
                                base: b,
                                index,
                                mutations,
                                keys,
                                outcome,
                                message,
                                stop,
                            },
                        ));
                        if outcome == Outcome::Hang {
                            // the hung thread keeps its directory; the lane moves to a new one
                            hangs += 1;
                            dir = root.join(format!("lane-{lane}-{hangs}"));
                        }
                    }
                    mine
                })
            })
            .collect();
        let mut all = Vec::new();
        for l in lanes {
            if let Ok(mine) = l.join() {
                all.extend(mine);
            }
        }
        all.sort_by_key(|(w, _)| *w);
        results = all.into_iter().map(|(_, r)| r).collect();
    });
    contactlab::scene::memory::set_memory_limit(previous_limit);
    let _ = std::fs::remove_dir_all(&root);
    summarize(c, &results, work.len(), report);
    Ok(())
}

/// Counts per model and outcome, the gates, and the examples.
fn summarize(c: &FuzzCase, results: &[SceneResult], planned: usize, report: &mut CaseReport) {
    let mut counts: BTreeMap<(String, Outcome), usize> = BTreeMap::new();
    let mut naming: BTreeMap<String, (usize, usize)> = BTreeMap::new();
    for r in results {
        *counts.entry((r.model.clone(), r.outcome)).or_default() += 1;
        if r.outcome == Outcome::Error {
            let e = naming.entry(r.model.clone()).or_default();
            e.0 += 1;
            if names_a_key(r) {
                e.1 += 1;
            }
        }
    }
    let models: Vec<String> = {
        let mut m: Vec<String> = c.base.iter().map(|b| b.model.clone()).collect();
        m.dedup();
        m.sort();
        m.dedup();
        m
    };
    let mut rows = Vec::new();
    let mut checks = Vec::new();
    for m in &models {
        let count = |o: Outcome| counts.get(&(m.clone(), o)).copied().unwrap_or(0);
        let total: usize = Outcome::ALL.iter().map(|&o| count(o)).sum();
        let (errors, named) = naming.get(m).copied().unwrap_or((0, 0));
        let mut row = vec![m.clone(), total.to_string()];
        row.extend(Outcome::ALL.iter().map(|&o| count(o).to_string()));
        row.push(format!("{named} of {errors}"));
        rows.push(row);
        // answered: every outcome but a hang (a defect is an answer, gated below at zero)
        checks.push(Check::at_least(
            &format!("{m}: scenes answered"),
            (total - count(Outcome::Hang)) as f64,
            c.scenes_per_model as f64,
        ));
        if let Some(share) = c.min_naming_share {
            // a verdict, not the share: which long scenes end in an error rather than a stop
            // depends on the machine's speed (the share is in the table's timing column)
            checks.push(Check::holds(
                &format!("{m}: errors naming the mutated key"),
                named as f64 >= share * errors as f64,
                &format!("at least {:.0} % of the errors", 100.0 * share),
            ));
        }
        for o in Outcome::ALL.into_iter().filter(|o| o.is_defect()) {
            checks.push(Check::at_most(
                &format!("{m}: {} outcomes", o.name()),
                count(o) as f64,
                0.0,
            ));
        }
    }
    checks.extend(stop_checks(&models, results, report));
    checks.push(Check::at_least(
        "every planned scene answered or was named as a hang",
        results.len() as f64,
        planned as f64,
    ));
    report.gates.push(GateVerdict::from_checks(
        format!(
            "fuzz: {} mutated scenes, no panic, hang or non-finite output",
            results.len()
        ),
        "extreme",
        checks,
        "each scene bounded by its own time limit (a stop naming its step is an answer, and must \
         be honoured at the first check that finds the limit passed: one fired check per thread \
         of the run, counted by the limit's clock); a defect is any panic, any scene silent beyond the limit plus \
         the grace, any written number that is not finite (in every output, also of runs that \
         ended in an error or a stop) and a stop reported as another error; with \
         min_naming_share, the share of errors that name the mutated key",
    ));
    // which of ran / error / stopped a long scene ends in depends on the machine's speed against
    // the time limit: those columns are timing-dependent (kept out of the deterministic report);
    // the defect columns are gated at zero
    let mut header: Vec<String> = vec!["model".into(), "scenes".into()];
    header.extend(Outcome::ALL.iter().map(|o| {
        if o.is_defect() {
            o.name().to_string()
        } else {
            format!("{} (timing: vs the limit)", o.name())
        }
    }));
    header.push("errors naming the mutated key (timing: vs the limit)".into());
    report.tables.push(Table {
        title: format!(
            "fuzz campaign (seed {}, time limit {} s per scene, memory limit {}): outcomes per model",
            c.seed, c.time_limit, c.max_memory
        ),
        header,
        rows,
    });
    unnamed_examples(c, results, report);
    // examples: the first scenes of every base, and every defect
    let mut rows = Vec::new();
    for r in results {
        if r.index >= EXAMPLES_PER_BASE && !r.outcome.is_defect() {
            continue;
        }
        let message = shortened(&r.message);
        rows.push(vec![
            r.model.clone(),
            format!("{}/{}/{}", c.seed, r.base, r.index),
            c.base[r.base].scene.display().to_string(),
            r.mutations.clone(),
            r.outcome.name().into(),
            message,
        ]);
    }
    report.tables.push(Table {
        title: "examples (reproduce with seed/base/index)".into(),
        header: [
            "model",
            "seed/base/index",
            "base scene",
            "mutations",
            "outcome (timing: vs the limit)",
            "message (timing: vs the limit)",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    });
}

/// The stops per model: every stop honoured at the first check that found the time limit passed
/// (gated: a loop that swallowed the stop and went on would check again), and a table of how late
/// the latest came, against the longest step measured before the limit.
fn stop_checks(models: &[String], results: &[SceneResult], report: &mut CaseReport) -> Vec<Check> {
    let mut checks = Vec::new();
    let mut rows = Vec::new();
    for m in models {
        let stops: Vec<&StopTiming> = results
            .iter()
            .filter(|r| &r.model == m)
            .filter_map(|r| r.stop.as_ref())
            .collect();
        let ignored = stops
            .iter()
            .filter(|t| !t.honoured_at_first_check())
            .count();
        checks.push(Check::at_most(
            &format!("{m}: stops not honoured at the first check after the time limit"),
            ignored as f64,
            0.0,
        ));
        let within = stops.iter().filter(|t| t.within_longest_step()).count();
        let latest_scene = results
            .iter()
            .filter(|r| &r.model == m)
            .filter_map(|r| Some((r.stop.as_ref()?.fired_after_limit?, r)))
            .max_by_key(|(late, _)| *late);
        let latest = latest_scene.map(|(l, _)| l).unwrap_or_default();
        let which = latest_scene.map_or(String::new(), |(_, r)| {
            format!("{}/{}: {}", r.base, r.index, r.mutations)
        });
        let longest = stops
            .iter()
            .map(|t| t.longest_step_before)
            .max()
            .unwrap_or_default();
        rows.push(vec![
            m.clone(),
            stops.len().to_string(),
            (stops.len() - ignored).to_string(),
            within.to_string(),
            format!("{:.4}", latest.as_secs_f64()),
            which,
            format!("{:.4}", longest.as_secs_f64()),
        ]);
    }
    report.tables.push(Table {
        title: "stops at the time limit (timing: vs the limit)".into(),
        header: [
            "model",
            "stopped (timing: vs the limit)",
            "honoured at the first check (timing: vs the limit)",
            "no later than the longest step before the limit (timing: vs the limit)",
            "latest stop after the limit, s (timing: vs the limit)",
            "its base/index and mutations (timing: vs the limit)",
            "longest step before the limit, s (timing: vs the limit)",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    });
    checks
}

/// Errors whose message does not name the mutated key shown per model.
const UNNAMED_PER_MODEL: usize = 12;

/// Whether an error's message names one of the mutated keys.
fn names_a_key(r: &SceneResult) -> bool {
    r.keys
        .iter()
        .any(|k| !k.is_empty() && r.message.contains(k.as_str()))
}

/// A table of the first errors per model whose message does not name the mutated key: what the
/// share of named errors leaves out, to read.
fn unnamed_examples(c: &FuzzCase, results: &[SceneResult], report: &mut CaseReport) {
    let mut shown: BTreeMap<&str, usize> = BTreeMap::new();
    let mut rows = Vec::new();
    for r in results {
        if r.outcome != Outcome::Error || names_a_key(r) {
            continue;
        }
        let n = shown.entry(r.model.as_str()).or_default();
        if *n >= UNNAMED_PER_MODEL {
            continue;
        }
        *n += 1;
        rows.push(vec![
            r.model.clone(),
            format!("{}/{}/{}", c.seed, r.base, r.index),
            r.mutations.clone(),
            shortened(&r.message),
        ]);
    }
    report.tables.push(Table {
        title: format!(
            "errors that do not name the mutated key (the first {UNNAMED_PER_MODEL} per model)"
        ),
        header: [
            "model (timing: vs the limit)",
            "seed/base/index (timing: vs the limit)",
            "mutations (timing: vs the limit)",
            "message (timing: vs the limit)",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect(),
        rows,
    });
}

/// `message` cut to its first and last 150 characters (at character boundaries): a run's
/// summary comes first, the failure last.
fn shortened(message: &str) -> String {
    if message.len() <= 300 {
        return message.to_string();
    }
    let head = (0..=150)
        .rev()
        .find(|&i| message.is_char_boundary(i))
        .unwrap_or(0);
    let tail = (message.len() - 150..message.len())
        .find(|&i| message.is_char_boundary(i))
        .unwrap_or(message.len());
    format!("{} … {}", &message[..head], &message[tail..])
}
