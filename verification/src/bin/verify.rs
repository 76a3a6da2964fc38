//! `cargo run --release --bin verify`: runs the verification cases, writes `reports/`, and exits
//! non-zero when a gate fails.
//!
//! - `verify`                       the default tier (quick + default cases, < 90 s), reports in `reports/default/`
//! - `verify --quick`               the CI tier (cases marked `tier = "quick"`, < 20 s), reports in `reports/quick/`
//! - `verify --full`                every case, the long studies too: the committed `reports/`
//! - `verify --case ID [--case ID]` selected cases
//! - `verify --shard I/N`           a deterministic 1/N of the run (balanced by recorded times)
//! - `verify merge DIR… --out OUT`  join the shards' directories into one run's report
//! - `verify --list`                the catalogue: tier and last measured time of every case
//! - `verify scene FILE.toml --out DIR [--max-memory 4G] [--max-disk 8G] [--vtk]`   run a user's scene (--vtk:
//!   also ParaView files)
//! - `verify compare BEFORE AFTER [--noise BEFORE2]`   are two report directories the same numbers?
//! - `verify readme [--check]`   the README's numbers, generated from reports/
//! - `verify scene-keys [--check]`   docs/scenes.md, generated from the scene types' doc comments
//! - `verify benches`   criterion's measurements against `benches/budgets.toml` (after `cargo bench`)
//! - `verify --quick --out DIR --check reports`   run, then fail when a deterministic number
//!   differs from the committed report of the same case (CI)

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use contactlab_verify::core::case::Tier;
use contactlab_verify::core::context::RunContext;
use contactlab_verify::core::report::benchmarks;
use contactlab_verify::core::report::compare::{check, compare};
use contactlab_verify::core::report::manifest::merge;
use contactlab_verify::core::report::metadata::Metadata;
use contactlab_verify::core::report::readme;
use contactlab_verify::core::shard::{recorded_seconds, Shard};
use contactlab_verify::registry;
use contactlab_verify::suite;

#[derive(Parser, Debug)]
#[command(
    name = "verify",
    about = "contactlab verification: exact solutions, rates, gates, reports"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// The CI tier: only cases with tier = "quick" (reports in reports/quick unless --out is given).
    #[arg(long, conflicts_with = "full")]
    quick: bool,
    /// Every case, the long studies too (reports in reports/, the committed ones, unless --out).
    #[arg(long)]
    full: bool,
    /// Run shard I of N of the selection (e.g. 2/3): a deterministic partition balanced by the
    /// run times recorded in reports/; join the N output directories with `verify merge`.
    #[arg(long, value_name = "I/N")]
    shard: Option<Shard>,
    /// Run only these cases (repeatable).
    #[arg(long = "case", value_name = "ID")]
    cases: Vec<String>,
    /// List the cases with their tier and last measured time, and exit.
    #[arg(long)]
    list: bool,
    /// The reports directory (default: <repository>/reports).
    #[arg(long)]
    out: Option<PathBuf>,
    /// The case directory (default: <repository>/verification/cases).
    #[arg(long)]
    cases_dir: Option<PathBuf>,
    /// Worker threads for sweeps (default: all cores). Results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// No progress bars.
    #[arg(long)]
    no_progress: bool,
    /// After the run, compare every case's deterministic numbers with its committed report in
    /// this directory (`reports`); exit 1 when any differs.
    #[arg(long, value_name = "DIR")]
    check: Option<PathBuf>,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run a scene file and write its solution (and errors, with an [exact] table) as JSON.
    Scene {
        /// The scene (TOML).
        file: PathBuf,
        /// Output directory.
        #[arg(long, default_value = "scene-out")]
        out: PathBuf,
        /// The most memory the run may hold (bytes, or with K, M, G, T): a scene whose estimate
        /// is above it is refused before anything is allocated (default: CONTACTLAB_MAX_MEMORY,
        /// else half of the machine's memory).
        #[arg(long)]
        max_memory: Option<String>,
        /// The most the run's files may take on disk (bytes, or with K, M, G, T): a scene whose
        /// files are estimated above it is refused before it runs (default: CONTACTLAB_MAX_DISK,
        /// else 8 GiB).
        #[arg(long)]
        max_disk: Option<String>,
        /// Stop the run after this many seconds (a typed error naming the step it reached; what
        /// the solver computed until then is written where the model records it).
        #[arg(long, value_name = "SECONDS")]
        time_limit: Option<f64>,
        /// Also write the ParaView files (as `[output] vtk = true`): one .vtu per output time and
        /// a solution.pvd collection with the time values, beside the JSON.
        #[arg(long)]
        vtk: bool,
    },
    /// Plan the cheapest mesh, step and scheme of a scene whose error must meet a target: pilot
    /// runs, fitted error and cost models, the choice (never above a stability bound, never
    /// beyond what the pilots support), and the chosen run against its prediction. Writes
    /// plan.json, plan.md and plan.svg. Rod scenes (against their [exact] solution, or by
    /// self-convergence without one); plane, dynamic and multibody scenes on generated shapes
    /// (self-convergence).
    Plan {
        /// The scene (TOML).
        file: PathBuf,
        /// The error the run must meet (in the functional's own units).
        #[arg(long)]
        target: f64,
        /// The functional whose error the target bounds (rod with [exact]: paper_E, the
        /// default, u_nodal_max, end_displacement, …; rod without: end_displacement, the
        /// default, contact_stress; plane: contact_force, the default, max_von_mises,
        /// max_displacement; dynamic: rebound_velocity_y (a bar: rebound_velocity), the
        /// default for a free body in contact, rebound_velocity_x, contact_force,
        /// max_von_mises, max_displacement (a bar: end_displacement); multibody:
        /// velocity_x.NAME, the default for the first body, velocity_y.NAME, contact_force,
        /// max_von_mises, max_displacement).
        #[arg(long)]
        functional: Option<String>,
        /// The schemes to choose among, comma-separated (default: all of the model's).
        #[arg(long, value_delimiter = ',')]
        schemes: Option<Vec<String>>,
        /// What the cost model is fitted on: `seconds` (measured CPU time) or `work` (the
        /// model's deterministic work count, e.g. M·N: the same plan on any machine).
        #[arg(long, default_value = "seconds")]
        cost: String,
        /// Pilot rounds: with more than 1, a target beyond what the pilots support runs the
        /// pilots again from the resolution the models propose (at most this many rounds).
        #[arg(long, default_value_t = 1)]
        rounds: usize,
        /// The first round's finest pilot M₀,N₀ (default: the scene's own mesh count and
        /// steps); the pilots run at (M₀/4 … M₀) × (N₀/4 … N₀).
        #[arg(long, value_name = "M0,N0")]
        base: Option<String>,
        /// Output directory.
        #[arg(long, default_value = "plan-out")]
        out: PathBuf,
    },
    /// Regenerate the README's numbers (its `<!-- generated: … -->` blocks) from reports/;
    /// with --check, exit 1 when they differ instead.
    Readme {
        #[arg(long)]
        check: bool,
    },
    /// Write docs/scenes.md, the reference of every scene key, from the scene types' fields and
    /// doc comments in src/; with --check, exit 1 when it differs instead.
    SceneKeys {
        #[arg(long)]
        check: bool,
    },
    /// Criterion's measurements (run `cargo bench` first) against the budgets of
    /// benches/budgets.toml: writes reports/benchmarks.md and .json; exit 1 when a budget is
    /// missed or unmeasured.
    Benches {
        /// The budgets (default: <repository>/benches/budgets.toml).
        #[arg(long)]
        budgets: Option<PathBuf>,
        /// Criterion's output (default: <repository>/target/criterion).
        #[arg(long)]
        criterion: Option<PathBuf>,
        /// Output directory (default: <repository>/reports).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Join the output directories of the shards 1/N … N/N of one run into the directory (and
    /// the report) of the unsharded run.
    Merge {
        /// The shards' output directories.
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
    },
    /// Compare two report directories: every number (and every non-prose text) must be equal;
    /// timings are left out. Exit 1 when they differ.
    Compare {
        /// The reports before a change.
        before: PathBuf,
        /// The reports after it.
        after: PathBuf,
        /// Further runs of the code of BEFORE (repeatable): leaves that differ between BEFORE
        /// and any of them are noise.
        #[arg(long)]
        noise: Vec<PathBuf>,
    },
}

fn repository_root() -> PathBuf {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().map(PathBuf::from).unwrap_or(manifest)
}

/// On a terminal, a progress bar of the running scene (steps, grid rows, sweep points), redrawn
/// from contactlab::run_control's counters four times a second until the flag is set.
fn scene_progress() -> Option<(
    std::sync::Arc<std::sync::atomic::AtomicBool>,
    std::thread::JoinHandle<()>,
)> {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return None;
    }
    let done = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let flag = done.clone();
    let handle = std::thread::spawn(move || {
        let bar = indicatif::ProgressBar::new(0);
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "{msg} {pos}/{len} [{bar:30}] {elapsed_precise} (eta {eta}); Ctrl-C stops and writes what there is",
        ) {
            bar.set_style(style);
        }
        while !flag.load(std::sync::atomic::Ordering::Relaxed) {
            let (label, n, total) = contactlab::run_control::progress();
            if total > 0 {
                bar.set_length(total);
                bar.set_position(n);
                bar.set_message(label);
            }
            std::thread::sleep(std::time::Duration::from_millis(250));
        }
        bar.finish_and_clear();
    });
    Some((done, handle))
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match &cli.command {
        Some(Command::Scene {
            file,
            out,
            max_memory,
            max_disk,
            time_limit,
            vtk,
        }) => {
            if let Some(seconds) = time_limit {
                match std::time::Duration::try_from_secs_f64(*seconds) {
                    Ok(d) => contactlab::run_control::set_time_limit(Some(d)),
                    Err(_) => {
                        eprintln!(
                            "error: invalid --time-limit = {seconds}: expected a number of seconds ≥ 0"
                        );
                        return ExitCode::from(2);
                    }
                }
            }
            // Ctrl-C: the solver stops at its next step (the handler only sets a flag)
            let _ = ctrlc::set_handler(contactlab::run_control::interrupt);
            if let Some(text) = max_memory {
                match contactlab::scene::memory::parse_size(text) {
                    Some(bytes) => contactlab::scene::memory::set_memory_limit(bytes),
                    None => {
                        eprintln!(
                            "error: invalid --max-memory = {text}: expected a size in bytes, e.g. 4G or 512M"
                        );
                        return ExitCode::from(2);
                    }
                }
            }
            if let Some(text) = max_disk {
                match contactlab::scene::memory::parse_size(text) {
                    Some(bytes) => contactlab::scene::memory::set_disk_limit(bytes),
                    None => {
                        eprintln!(
                            "error: invalid --max-disk = {text}: expected a size in bytes, e.g. 8G or 512M"
                        );
                        return ExitCode::from(2);
                    }
                }
            }
            let progress = scene_progress();
            let result = registry::run_scene_with(file, out, *vtk);
            if let Some((done, handle)) = progress {
                done.store(true, std::sync::atomic::Ordering::Relaxed);
                let _ = handle.join();
            }
            return match result {
                Ok(summary) => {
                    println!("{summary}");
                    println!("wrote {}", out.display());
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
            };
        }
        Some(Command::Plan {
            file,
            target,
            functional,
            schemes,
            cost,
            rounds,
            base,
            out,
        }) => {
            use contactlab_verify::core::plan::CostMeasure;
            let cost = match cost.as_str() {
                "seconds" => CostMeasure::Seconds,
                "work" => CostMeasure::Work,
                other => {
                    eprintln!("error: --cost = {other}: expected `seconds` or `work`");
                    return ExitCode::from(2);
                }
            };
            let request = contactlab_verify::core::plan::PlanRequest {
                target: *target,
                functional: functional.clone().unwrap_or_default(),
                schemes: schemes.clone(),
                cost,
                rounds: *rounds,
            };
            if let Err(e) = request.validate() {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
            let base = match base.as_deref().map(|b| {
                let v: Vec<Option<usize>> = b.split(',').map(|x| x.trim().parse().ok()).collect();
                match v.as_slice() {
                    [Some(m), Some(n)] => Ok((*m, *n)),
                    _ => Err(b.to_string()),
                }
            }) {
                None => None,
                Some(Ok(b)) => Some(b),
                Some(Err(b)) => {
                    eprintln!("error: --base {b}: expected two counts M0,N0 (e.g. 16,400)");
                    return ExitCode::from(2);
                }
            };
            return match contactlab_verify::registry::plan_scene(file, &request, base, out) {
                Ok(md) => {
                    println!("{md}\n(written to {})", out.display());
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::FAILURE
                }
            };
        }
        Some(Command::Merge { dirs, out }) => {
            return match merge(dirs, out) {
                Ok(m) => {
                    let failed = m.manifest.cases.iter().filter(|c| !c.passed).count();
                    println!(
                        "merged {} shards: {} case(s), {} failed; report: {}",
                        m.manifest.shard_count,
                        m.manifest.cases.len(),
                        failed,
                        m.report.display()
                    );
                    if failed > 0 {
                        ExitCode::from(1)
                    } else {
                        ExitCode::SUCCESS
                    }
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
            };
        }
        Some(Command::Compare {
            before,
            after,
            noise,
        }) => {
            return match compare(before, after, noise) {
                Ok(c) => {
                    print!("{}", c.render());
                    if c.same() {
                        println!("same numbers");
                        ExitCode::SUCCESS
                    } else {
                        println!("the reports differ");
                        ExitCode::from(1)
                    }
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
            };
        }
        Some(Command::SceneKeys { check }) => {
            return contactlab_verify::scene_keys::run_command(&repository_root(), *check);
        }
        Some(Command::Readme { check }) => {
            let root = repository_root();
            let path = root.join("README.md");
            let result = std::fs::read_to_string(&path)
                .map_err(|e| format!("{}: {e}", path.display()))
                .and_then(|text| {
                    let blocks = readme::render(&root.join("reports"))?;
                    Ok((readme::fill(&text, &blocks)?, text))
                });
            return match result {
                Ok((new, old)) if *check => {
                    if new == old {
                        println!("README.md: the numbers equal the reports'");
                        ExitCode::SUCCESS
                    } else {
                        println!(
                            "README.md: the numbers differ from the reports' (run `verify readme`)"
                        );
                        ExitCode::from(1)
                    }
                }
                Ok((new, _)) => match std::fs::write(&path, new) {
                    Ok(()) => {
                        println!("wrote {}", path.display());
                        ExitCode::SUCCESS
                    }
                    Err(e) => {
                        eprintln!("error: {}: {e}", path.display());
                        ExitCode::from(2)
                    }
                },
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
            };
        }
        Some(Command::Benches {
            budgets,
            criterion,
            out,
        }) => {
            let root = repository_root();
            let budgets = budgets
                .clone()
                .unwrap_or_else(|| root.join("benches/budgets.toml"));
            let criterion = criterion
                .clone()
                .unwrap_or_else(|| root.join("target/criterion"));
            let out = out.clone().unwrap_or_else(|| root.join("reports"));
            return match benchmarks::collect(&budgets, &criterion) {
                Ok(r) => {
                    let md = r.markdown();
                    print!("{md}");
                    let json = serde_json::to_string_pretty(&r).unwrap_or_default();
                    for (name, text) in [("benchmarks.md", md), ("benchmarks.json", json)] {
                        let path = out.join(name);
                        if let Err(e) = std::fs::write(&path, text) {
                            eprintln!("error: writing {}: {e}", path.display());
                            return ExitCode::from(2);
                        }
                    }
                    if r.passed() {
                        ExitCode::SUCCESS
                    } else {
                        ExitCode::from(1)
                    }
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
            };
        }
        None => {}
    }
    if let Some(n) = cli.threads {
        if let Err(e) = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
        {
            eprintln!("error: --threads {n}: {e}");
            return ExitCode::from(2);
        }
    }
    let root = repository_root();
    let cases_dir = cli
        .cases_dir
        .clone()
        .unwrap_or_else(|| root.join("verification/cases"));
    let cases = match registry::load_all(&cases_dir) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let ids: Vec<String> = cases.iter().map(|c| c.header.id.clone()).collect();
    let recorded = recorded_seconds(&root.join("reports"), &ids);
    if cli.list {
        print!("{}", suite::list::render(&cases, &recorded));
        return ExitCode::SUCCESS;
    }
    let tier = if cli.quick {
        Tier::Quick
    } else if cli.full {
        Tier::Full
    } else {
        Tier::Default
    };
    let shard = cli.shard.unwrap_or(Shard::WHOLE);
    let selection = match suite::select::select(&cases, tier, &cli.cases, shard, &recorded) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let out = cli.out.clone().unwrap_or_else(|| match tier {
        Tier::Full => root.join("reports"),
        t => root.join("reports").join(t.name()),
    });
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("error: cannot create {}: {e}", out.display());
        return ExitCode::from(2);
    }
    let mut ctx = RunContext {
        out_dir: out.clone(),
        metadata: Metadata::collect(tier.name()),
        progress: !cli.no_progress,
        bars: None,
    };
    let outcome = match suite::run::run(&selection, &mut ctx, tier.name(), shard) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let reports = &outcome.reports;
    print!(
        "{}",
        suite::run::summary_table(reports, &selection.expected, shard)
    );
    let failed = reports.iter().filter(|r| !r.passed).count();
    println!(
        "wall time {:.1} s; report: {}",
        outcome.total_seconds,
        outcome.report_path.display()
    );
    let mut drifted = false;
    if let Some(reference) = &cli.check {
        let ids: Vec<String> = reports.iter().map(|r| r.id.clone()).collect();
        match check(reference, &out, &ids) {
            Ok(c) => {
                print!("{}", c.render());
                if c.same() {
                    println!(
                        "check: the deterministic numbers equal {}",
                        reference.display()
                    );
                } else {
                    println!(
                        "check: the deterministic numbers differ from {} (regenerate the reports \
                         at the commit that changes them)",
                        reference.display()
                    );
                    drifted = true;
                }
            }
            Err(e) => {
                eprintln!("error: --check {}: {e}", reference.display());
                return ExitCode::from(2);
            }
        }
    }
    if failed > 0 || drifted {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}
