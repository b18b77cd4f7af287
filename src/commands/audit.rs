//! `audit`: recompute a sample of a run folder's stored job results with this build and
//! compare them byte for byte ([`persson_check::tasks::audit`]). One line per job on
//! stdout, a progress bar on a terminal; exit code 0 when every job that ran is identical,
//! 1 when one differs or failed, 2 on bad input.

use std::path::PathBuf;
use std::time::Duration;

use clap::Args as ClapArgs;
use indicatif::{ProgressBar, ProgressStyle};
use persson_check::error::Result;
use persson_check::tasks::audit::{
    audit, minutes, parse_budget, AuditOptions, Event, DEFAULT_BUDGET_S,
};
use persson_check::validation::Registry;

/// Arguments of `audit`.
#[derive(ClapArgs, Debug)]
pub struct Args {
    /// The run folder whose stored job results (<from>/jobs/) are audited.
    #[arg(long, default_value = "results/full")]
    from: PathBuf,
    /// Wall-time budget (90s, 20m, 2h): jobs are sampled while their estimated total,
    /// times 1.5, fits. Default 20m; with --validation alone, every job of it.
    #[arg(long)]
    budget: Option<String>,
    /// Seed of the random part of the sample.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Recompute these jobs (keys: their result files' names), whatever the budget.
    #[arg(long = "job", num_args = 1..)]
    jobs: Vec<String>,
    /// Only the jobs these validations need.
    #[arg(long = "validation", num_args = 1..)]
    validations: Vec<String>,
    /// Folder for audit.md and audit.json.
    #[arg(long, default_value = "audit")]
    out: PathBuf,
}

/// Audits; whether every sampled job is identical.
pub fn run(args: Args) -> Result<bool> {
    let budget_s = match &args.budget {
        Some(text) => Some(parse_budget(text)?),
        None if args.jobs.is_empty() && args.validations.is_empty() => Some(DEFAULT_BUDGET_S),
        None => None,
    };
    let opts = AuditOptions {
        from: args.from,
        out: args.out,
        budget_s,
        seed: args.seed,
        jobs: args.jobs,
        validations: args.validations,
    };
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template(
            "{prefix:>8} [{elapsed_precise}] {bar:30} {pos}/{len} jobs {msg}",
        )
        .expect("static template"),
    );
    bar.set_prefix("audit");
    bar.enable_steady_tick(Duration::from_secs(1));
    let result = audit(&Registry::builtin(), &opts, &mut |event| match event {
        Event::Planned(n, estimate) => {
            bar.set_length(n as u64);
            bar.suspend(|| {
                outln!(
                    "{n} job{} sampled, estimated {} on one core",
                    if n == 1 { "" } else { "s" },
                    minutes(estimate)
                )
            });
        }
        Event::Started(_, c) => bar.set_message(format!(
            "{} ({}, {})",
            c.key,
            c.validations.join("+"),
            c.solver.name()
        )),
        Event::Done(job) => {
            bar.suspend(|| outln!("{}", job.line()));
            bar.inc(1);
        }
    });
    bar.finish_and_clear();
    let audit = result?;
    outln!("{}", audit.summary);
    outln!(
        "wrote {} and {}",
        opts.out.join("audit.md").display(),
        opts.out.join("audit.json").display()
    );
    Ok(audit.passed)
}
