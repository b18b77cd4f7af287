//! What a history does shell by shell (paper section 3.3): the points that enter and leave
//! contact at every added shell, and how long a stretch of contact lasts once a point has
//! re-entered.
//!
//! Two statements of the paper read on these counts:
//!
//! * "sharp features all come from low magnifications where the surface changes relatively
//!   strongly with each added wave number" (fig. reentry_visualization_allQ caption, tex
//!   817-818): the changes of contact state per added shell, per point of the contact
//!   before the shell, `c_k = (entered_k + left_k) / contact_{k-1}`, averaged over the
//!   shells of the first octave of the range (`zeta_1 < zeta <= 2 zeta_1`, the first step
//!   itself excluded: it starts from the flat interface) minus the average over the last
//!   octave (`zeta_max / 2 < zeta <= zeta_max`);
//! * "one may expect a re-entry contact point to get out of contact soon again" (tex
//!   758-760): of the points that entered contact at a shell `e`, the share that left again
//!   within [`SOON`] shells, minus the same share for every point in contact at any shell.
//!   The second is counted over every (point, shell) pair with the point in contact at the
//!   shell: a stretch of contact from shell `e` that ends at shell `t` holds `min(SOON, t -
//!   e)` pairs that leave within [`SOON`] shells. Only shells at least [`SOON`] before the
//!   last count, so every pair and entry is followed for the whole window.

use serde::{Deserialize, Serialize};

use super::stats::ratio;
use crate::error::{Error, Result};
use crate::experiments::climb::Arrays;
use crate::experiments::contact_change::above;
use crate::io::checkpoint::{Array, Checkpoints};
use crate::stats::Estimate;

/// How many shells count as "soon".
pub const SOON: usize = 10;

/// The per-shell record of one history, as stored with its result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ShellRecord {
    /// Magnification of every step.
    pub zeta: Vec<f64>,
    /// Points entering contact at every step.
    pub entered: Vec<u32>,
    /// Points leaving contact at every step.
    pub left: Vec<u32>,
    /// Points in contact after every step.
    pub contact: Vec<u32>,
    /// Entries into contact at a step at least [`SOON`] before the last.
    pub entries: u64,
    /// Of those, entries followed by a departure within [`SOON`] shells.
    pub entries_left_soon: u64,
    /// (Point, step) pairs in contact, steps at least [`SOON`] before the last.
    pub contact_pairs: u64,
    /// Of those, pairs whose point leaves contact within [`SOON`] shells.
    pub contact_pairs_left_soon: u64,
}

impl ShellRecord {
    /// Of the entries, the share that left again within [`SOON`] shells, minus that share
    /// for every point in contact.
    pub fn leave_soon_excess(&self) -> f64 {
        self.entered_leave_soon() - self.contact_leave_soon()
    }

    /// Of the entries into contact, the share that left within [`SOON`] shells.
    pub fn entered_leave_soon(&self) -> f64 {
        ratio(self.entries_left_soon, self.entries)
    }

    /// Of the points in contact at a shell, the share that leaves within [`SOON`] shells.
    pub fn contact_leave_soon(&self) -> f64 {
        ratio(self.contact_pairs_left_soon, self.contact_pairs)
    }

    /// Changes of contact state per shell and per point of the contact before it, averaged
    /// over the shells of `(lo, hi]` (the first step excluded); `None` if none lies there.
    fn changes_in(&self, lo: f64, hi: f64) -> Option<f64> {
        let rates: Vec<f64> = (1..self.zeta.len())
            .filter(|&k| self.zeta[k] > lo && self.zeta[k] <= hi)
            .map(|k| {
                f64::from(self.entered[k] + self.left[k]) / f64::from(self.contact[k - 1].max(1))
            })
            .collect();
        (!rates.is_empty()).then(|| rates.iter().sum::<f64>() / rates.len() as f64)
    }

    /// The changes per shell in the first octave of the range.
    pub fn changes_first_octave(&self) -> Option<f64> {
        let first = *self.zeta.first()?;
        self.changes_in(first, 2.0 * first)
    }

    /// The changes per shell in the last octave of the range.
    pub fn changes_last_octave(&self) -> Option<f64> {
        let last = *self.zeta.last()?;
        self.changes_in(0.5 * last, last)
    }

    /// The first octave's changes per shell minus the last's.
    pub fn changes_octave_drop(&self) -> Option<f64> {
        Some(self.changes_first_octave()? - self.changes_last_octave()?)
    }
}

/// Records a history shell by shell; it sees each step before the history does.
#[derive(Debug, Clone)]
pub struct ShellLog {
    /// Index of the last step.
    last: usize,
    /// 1 where the point is in contact after the last recorded step.
    in_contact: Vec<u8>,
    /// The step at which the point's present stretch of contact began (0: in contact
    /// since the flat interface, or since the first step).
    since: Vec<u16>,
    record: ShellRecord,
}

/// Checkpoint metadata of a shell log.
#[derive(Serialize, Deserialize)]
struct Meta {
    record: ShellRecord,
}

impl ShellLog {
    /// A log of `points` points, all in contact, over `steps` steps; errors if the steps do
    /// not fit the stored step numbers.
    pub fn new(points: usize, steps: usize) -> Result<Self> {
        if steps == 0 || steps > usize::from(u16::MAX) {
            return Err(Error::invalid(
                "record_shells",
                steps,
                format!("a history of 1 to {} steps", u16::MAX),
            ));
        }
        Ok(Self {
            last: steps - 1,
            in_contact: vec![1; points],
            since: vec![0; points],
            record: ShellRecord {
                zeta: Vec::with_capacity(steps),
                entered: Vec::with_capacity(steps),
                left: Vec::with_capacity(steps),
                contact: Vec::with_capacity(steps),
                entries: 0,
                entries_left_soon: 0,
                contact_pairs: 0,
                contact_pairs_left_soon: 0,
            },
        })
    }

    /// Records step `step` at magnification `zeta` with the contact pressure `pressure`.
    pub fn update(&mut self, step: usize, zeta: f64, pressure: &[f64]) {
        let horizon = self.last.saturating_sub(SOON);
        let observed = self.last >= SOON;
        let (mut entered, mut left, mut contact) = (0u32, 0u32, 0u32);
        let r = &mut self.record;
        for (i, &p) in pressure.iter().enumerate() {
            let now = u8::from(above(p, 0.0));
            match (self.in_contact[i], now) {
                (0, 1) => {
                    entered += 1;
                    self.since[i] = step as u16;
                    r.entries += u64::from(observed && step <= horizon);
                }
                (1, 0) => {
                    left += 1;
                    let from = usize::from(self.since[i]);
                    // A stretch that began with an entry (not at the flat interface or the
                    // first step) and ends within the window.
                    if from > 0 && from <= horizon && step - from <= SOON {
                        r.entries_left_soon += 1;
                    }
                    // The pairs of the stretch that leave within the window.
                    if observed && step > 0 {
                        let lo = from.max(step.saturating_sub(SOON));
                        let hi = (step - 1).min(horizon);
                        if hi >= lo {
                            r.contact_pairs_left_soon += (hi - lo + 1) as u64;
                        }
                    }
                }
                _ => {}
            }
            contact += u32::from(now);
            self.in_contact[i] = now;
        }
        if observed && step <= horizon {
            r.contact_pairs += u64::from(contact);
        }
        r.zeta.push(zeta);
        r.entered.push(entered);
        r.left.push(left);
        r.contact.push(contact);
    }

    /// The record so far.
    pub fn record(&self) -> &ShellRecord {
        &self.record
    }

    /// The record, once the history is done.
    pub fn into_record(self) -> ShellRecord {
        self.record
    }

    /// The state to checkpoint.
    pub fn state(&self) -> (serde_json::Value, Arrays<'_>) {
        let meta = Meta {
            record: self.record.clone(),
        };
        (
            serde_json::to_value(meta).expect("checkpoint metadata serialises"),
            vec![
                ("shells_in_contact", Array::U8(&self.in_contact)),
                ("shells_since", Array::U16(&self.since)),
            ],
        )
    }

    /// Restores the state saved by [`ShellLog::state`].
    pub fn restore(&mut self, meta: serde_json::Value, ck: &Checkpoints) -> Result<()> {
        let meta: Meta = serde_json::from_value(meta)
            .map_err(|e| Error::invalid("checkpoint", e, "a shell record"))?;
        self.record = meta.record;
        self.in_contact = ck.load_u8("shells_in_contact")?;
        self.since = ck.load_u16("shells_since")?;
        Ok(())
    }
}

/// The statistics of one load's shell records, means over realizations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShellStats {
    /// Of the entries into contact, the share that left within [`SOON`] shells.
    pub entered_leave_soon: Estimate,
    /// Of the points in contact at a shell, the share that leaves within [`SOON`] shells.
    pub contact_leave_soon: Estimate,
    /// The first minus the second.
    pub leave_soon_excess: Estimate,
    /// Changes of contact state per shell and point of contact, first octave.
    pub changes_first_octave: Estimate,
    /// The same in the last octave.
    pub changes_last_octave: Estimate,
    /// The first octave's minus the last's.
    pub changes_octave_drop: Estimate,
}

impl ShellStats {
    /// The statistics of `records` (none without records).
    pub fn of(records: &[&ShellRecord]) -> Option<Self> {
        if records.is_empty() {
            return None;
        }
        let mean = |f: &dyn Fn(&ShellRecord) -> Option<f64>| {
            Estimate::mean_of(&records.iter().filter_map(|r| f(r)).collect::<Vec<_>>())
        };
        Some(Self {
            entered_leave_soon: mean(&|r| Some(r.entered_leave_soon())),
            contact_leave_soon: mean(&|r| Some(r.contact_leave_soon())),
            leave_soon_excess: mean(&|r| Some(r.leave_soon_excess())),
            changes_first_octave: mean(&ShellRecord::changes_first_octave),
            changes_last_octave: mean(&ShellRecord::changes_last_octave),
            changes_octave_drop: mean(&ShellRecord::changes_octave_drop),
        })
    }
}

/// The statistics of [`ShellStats`] a variant reports, by name (the middle of its detail
/// keys, after the variant's name and before the load).
pub const STATISTICS: [&str; 6] = [
    "leave_soon_excess",
    "entered_leave_soon",
    "contact_leave_soon",
    "changes_octave_drop",
    "changes_first_octave",
    "changes_last_octave",
];

impl ShellStats {
    /// Each of [`STATISTICS`] with its description (at load `a` of a variant `what`, in
    /// words), in that order.
    pub fn labels(a: f64, what: &str) -> [(&'static str, String); 6] {
        let per_shell = "changes of contact state per added shell and point of contact";
        let texts = [
            format!(
                "of the points entering contact, the share leaving again within {SOON} \
                 shells, minus that of every point in contact"
            ),
            format!(
                "of the points entering contact, the share leaving again within {SOON} \
                 shells"
            ),
            format!("of the points in contact at a shell, the share leaving within {SOON} shells"),
            format!("{per_shell}, first octave of zeta minus last octave"),
            format!("{per_shell}, first octave of zeta (the first shell excluded)"),
            format!("{per_shell}, last octave of zeta"),
        ];
        std::array::from_fn(|k| (STATISTICS[k], format!("{}, a_r = {a}, {what}", texts[k])))
    }

    /// The value of each of [`STATISTICS`], in that order.
    pub fn values(&self) -> [Estimate; 6] {
        [
            self.leave_soon_excess,
            self.entered_leave_soon,
            self.contact_leave_soon,
            self.changes_octave_drop,
            self.changes_first_octave,
            self.changes_last_octave,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The log of `states` (1 in contact) of a few points.
    fn run(states: &[&[u8]]) -> ShellRecord {
        let mut log = ShellLog::new(states[0].len(), states.len()).unwrap();
        for (k, s) in states.iter().enumerate() {
            let p: Vec<f64> = s.iter().map(|&c| f64::from(c)).collect();
            log.update(k, 1.0 + k as f64, &p);
        }
        log.record
    }

    #[test]
    fn per_shell_counts_follow_the_states() {
        let r = run(&[&[1, 0, 1], &[0, 1, 1], &[0, 1, 0]]);
        assert_eq!(r.entered, vec![0, 1, 0]);
        assert_eq!(r.left, vec![1, 1, 1]);
        assert_eq!(r.contact, vec![2, 2, 1]);
        assert_eq!(r.zeta, vec![1.0, 2.0, 3.0]);
    }

    #[test]
    fn leaving_soon_counts_entries_and_contact_pairs_by_brute_force() {
        // Point 0 re-enters at step 2 and leaves at step 5 (within SOON); point 1 enters
        // at step 3 and stays; point 2 is in contact throughout; point 3 leaves at step 14.
        let steps = 30;
        let mut states = vec![vec![1u8; 4]; steps];
        for (k, s) in states.iter_mut().enumerate() {
            s[0] = u8::from(!(k == 1 || k >= 5));
            s[1] = u8::from(k >= 3);
            s[3] = u8::from(k < 14);
        }
        let refs: Vec<&[u8]> = states.iter().map(|s| &s[..]).collect();
        let r = run(&refs);
        assert_eq!((r.entries, r.entries_left_soon), (2, 1));
        // Brute force: every (point, step) in contact at steps <= last - SOON, and
        // whether the point is out at some step within the next SOON.
        let horizon = steps - 1 - SOON;
        let (mut pairs, mut soon) = (0, 0);
        for (k, state) in states.iter().enumerate().take(horizon + 1) {
            for (i, &c) in state.iter().enumerate() {
                if c == 1 {
                    pairs += 1;
                    soon += u64::from((k + 1..=k + SOON).any(|t| states[t][i] == 0));
                }
            }
        }
        assert_eq!((r.contact_pairs, r.contact_pairs_left_soon), (pairs, soon));
        assert!((r.leave_soon_excess() - (0.5 - soon as f64 / pairs as f64)).abs() < 1e-15);
    }

    #[test]
    fn octaves_average_the_changes_per_point_of_contact() {
        let r = ShellRecord {
            zeta: vec![1.0, 1.5, 2.0, 3.0, 4.0],
            entered: vec![0, 1, 0, 0, 0],
            left: vec![5, 1, 2, 1, 0],
            contact: vec![10, 10, 8, 7, 7],
            entries: 0,
            entries_left_soon: 0,
            contact_pairs: 0,
            contact_pairs_left_soon: 0,
        };
        // First octave (1, 2]: 2/10 and 2/10; last octave (2, 4]: 1/8 and 0/7.
        assert!((r.changes_first_octave().unwrap() - 0.2).abs() < 1e-15);
        assert!((r.changes_last_octave().unwrap() - 0.0625).abs() < 1e-15);
        assert!((r.changes_octave_drop().unwrap() - 0.1375).abs() < 1e-15);
    }

    #[test]
    fn a_history_too_long_for_the_step_numbers_is_refused() {
        let err = ShellLog::new(4, 70_000).unwrap_err().to_string();
        assert!(err.contains("record_shells"), "{err}");
    }

    #[test]
    fn a_log_restored_from_its_checkpoint_ends_as_an_uninterrupted_one() {
        // Seven points whose states change at pseudo-random steps.
        let state = |k: usize, i: usize| u8::from((k * 7 + i * 13) % 5 != 0 || k < 2);
        let pressure = |k: usize| (0..7).map(|i| f64::from(state(k, i))).collect::<Vec<_>>();
        let steps = 40;
        let mut whole = ShellLog::new(7, steps).unwrap();
        for k in 0..steps {
            whole.update(k, 1.0 + k as f64, &pressure(k));
        }
        let dir = tempfile::tempdir().unwrap();
        let mut first = ShellLog::new(7, steps).unwrap();
        for k in 0..17 {
            first.update(k, 1.0 + k as f64, &pressure(k));
        }
        let mut ck = Checkpoints::new(dir.path());
        let (meta, arrays) = first.state();
        ck.save(&meta, &arrays).unwrap();
        let mut ck = Checkpoints::new(dir.path());
        let meta: serde_json::Value = ck.load_meta().unwrap();
        let mut resumed = ShellLog::new(7, steps).unwrap();
        resumed.restore(meta, &ck).unwrap();
        for k in 17..steps {
            resumed.update(k, 1.0 + k as f64, &pressure(k));
        }
        assert_eq!(resumed.record(), whole.record());
        assert!(whole.record().entries > 0 && whole.record().contact_pairs_left_soon > 0);
    }
}
