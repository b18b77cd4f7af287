//! The contact history of every point of a climb: how often it left contact and how often
//! it came back, and the flux into and out of contact over one interval of magnification.

use serde::{Deserialize, Serialize};

use crate::engine::climb::{Arrays, Recorder};
use crate::engine::contact::ContactSolution;
use crate::engine::contact_change::{above, change, ENTERED, LEFT};
use crate::engine::tolerance::ZETA_SLACK;
use crate::error::Result;
use crate::io::checkpoint::{Array, Checkpoints};

/// Map category: in contact at every step (grey).
pub const IN_THROUGHOUT: u8 = 0;
/// Map category: in contact, after having been out (red: re-entered).
pub const REENTERED: u8 = 1;
/// Map category: out of contact, never back (white).
pub const OUT_FOR_GOOD: u8 = 2;
/// Map category: out of contact after having come back at least once (blue).
pub const OUT_AFTER_RETURN: u8 = 3;

/// What happened over the flux interval: fractions of the nominal area that entered and
/// left contact, the share of the non-contact at its start that entered, and the map of
/// the changes (0 in contact at both ends, 1 entered, 2 out at both ends, 3 left).
#[derive(Debug, Clone, PartialEq)]
pub struct Flux {
    /// Fraction of the nominal area entering contact.
    pub into: f64,
    /// Fraction of the nominal area leaving contact.
    pub out_of: f64,
    /// Share of the non-contact at the start that is in contact at the end.
    pub into_of_noncontact: f64,
    /// Change of every point.
    pub map: Vec<u8>,
}

/// The per-point history of a climb from the flat interface (every point in contact).
#[derive(Debug, Clone)]
pub struct History {
    /// The interval `(zeta_from, zeta_to]` whose flux is measured.
    flux_interval: (f64, f64),
    /// 1 where the point is in contact after the last recorded step.
    pub in_contact: Vec<u8>,
    /// Departures from contact.
    pub left: Vec<u16>,
    /// Returns into contact.
    pub returned: Vec<u16>,
    /// 1 where the point left contact after the first step.
    pub left_after_first: Vec<u8>,
    flux_start: Option<Vec<u8>>,
    /// The flux over the interval, once closed.
    pub flux: Option<Flux>,
}

/// Checkpoint metadata of a history.
#[derive(Serialize, Deserialize)]
struct Meta {
    flux: Option<(f64, f64, f64)>,
    has_flux_start: bool,
}

impl History {
    /// A history of `points` points, all in contact, measuring the flux over
    /// `(zeta_from, zeta_to]`.
    pub fn new(points: usize, flux_interval: (f64, f64)) -> Self {
        Self {
            flux_interval,
            in_contact: vec![1; points],
            left: vec![0; points],
            returned: vec![0; points],
            left_after_first: vec![0; points],
            flux_start: None,
            flux: None,
        }
    }

    /// Records the contact state after step `step` (0 = first shell).
    pub fn update(&mut self, step: usize, pressure: &[f64]) {
        for (i, &p) in pressure.iter().enumerate() {
            let now = u8::from(above(p, 0.0));
            let was = self.in_contact[i];
            if was == 1 && now == 0 {
                self.left[i] = self.left[i].saturating_add(1);
                if step > 0 {
                    self.left_after_first[i] = 1;
                }
            } else if was == 0 && now == 1 {
                self.returned[i] = self.returned[i].saturating_add(1);
            }
            self.in_contact[i] = now;
        }
    }

    /// Closes the flux interval if it is open: fluxes against the state at its start.
    pub fn close_flux(&mut self) {
        let Some(start) = self.flux_start.as_ref() else {
            return;
        };
        if self.flux.is_some() {
            return;
        }
        let n = start.len() as f64;
        let (mut enter, mut leave, mut out_before) = (0.0, 0.0, 0.0);
        let mut map = Vec::with_capacity(start.len());
        for (&a, &b) in start.iter().zip(&self.in_contact) {
            out_before += f64::from(1 - a);
            let c = change(a == 1, b == 1);
            match c {
                ENTERED => enter += 1.0,
                LEFT => leave += 1.0,
                _ => {}
            }
            map.push(c);
        }
        let into_of_noncontact = if out_before > 0.0 {
            enter / out_before
        } else {
            0.0
        };
        self.flux = Some(Flux {
            into: enter / n,
            out_of: leave / n,
            into_of_noncontact,
            map,
        });
    }

    /// The map category of every point (see [`IN_THROUGHOUT`] and the others).
    pub fn categories(&self) -> Vec<u8> {
        self.in_contact
            .iter()
            .zip(self.left.iter().zip(&self.returned))
            .map(|(&c, (&l, &r))| match (c, l > 0, r > 0) {
                (1, false, _) => IN_THROUGHOUT,
                (1, true, _) => REENTERED,
                (_, _, false) => OUT_FOR_GOOD,
                _ => OUT_AFTER_RETURN,
            })
            .collect()
    }

    /// Points in contact now; of those, points that were ever out; and points that left
    /// after the first step.
    pub fn counts(&self) -> (u64, u64, u64) {
        let (mut contact, mut reentered, mut after_first) = (0, 0, 0);
        for i in 0..self.in_contact.len() {
            if self.in_contact[i] == 1 {
                contact += 1;
                reentered += u64::from(self.left[i] > 0);
                after_first += u64::from(self.left_after_first[i] == 1);
            }
        }
        (contact, reentered, after_first)
    }
}

impl Recorder for History {
    fn record(&mut self, step: usize, zeta: f64, solution: &ContactSolution) -> Result<()> {
        // The interval opens with the state before its first step and closes with the
        // state after its last one.
        let (from, to) = self.flux_interval;
        if self.flux_start.is_none() && zeta > from * (1.0 + ZETA_SLACK) {
            self.flux_start = Some(self.in_contact.clone());
        }
        if zeta > to * (1.0 + ZETA_SLACK) {
            self.close_flux();
        }
        self.update(step, &solution.pressure);
        Ok(())
    }

    fn state(&self) -> (serde_json::Value, Arrays<'_>) {
        let meta = Meta {
            flux: self
                .flux
                .as_ref()
                .map(|f| (f.into, f.out_of, f.into_of_noncontact)),
            has_flux_start: self.flux_start.is_some(),
        };
        let arrays = vec![
            ("in_contact", Array::U8(&self.in_contact)),
            ("left", Array::U16(&self.left)),
            ("returned", Array::U16(&self.returned)),
            ("left_after_first", Array::U8(&self.left_after_first)),
            (
                "flux_start",
                Array::U8(self.flux_start.as_deref().unwrap_or(&[])),
            ),
            (
                "flux_map",
                Array::U8(self.flux.as_ref().map_or(&[][..], |f| &f.map[..])),
            ),
        ];
        (
            serde_json::to_value(meta).expect("checkpoint metadata serialises"),
            arrays,
        )
    }

    fn restore(&mut self, meta: serde_json::Value, ck: &Checkpoints) -> Result<()> {
        let meta: Meta = serde_json::from_value(meta)
            .map_err(|e| crate::error::Error::invalid("checkpoint", e, "a re-entry history"))?;
        self.in_contact = ck.load_u8("in_contact")?;
        self.left = ck.load_u16("left")?;
        self.returned = ck.load_u16("returned")?;
        self.left_after_first = ck.load_u8("left_after_first")?;
        self.flux_start = if meta.has_flux_start {
            Some(ck.load_u8("flux_start")?)
        } else {
            None
        };
        self.flux = match meta.flux {
            Some((into, out_of, into_of_noncontact)) => Some(Flux {
                into,
                out_of,
                into_of_noncontact,
                map: ck.load_u8("flux_map")?,
            }),
            None => None,
        };
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn history_counts_departures_and_returns() {
        let mut h = History::new(3, (1.0, 2.0));
        h.update(0, &[1.0, 0.0, 0.0]);
        h.update(1, &[0.0, 1.0, 0.0]);
        h.update(2, &[1.0, 1.0, 0.0]);
        assert_eq!(h.left, vec![1, 1, 1]);
        assert_eq!(h.returned, vec![1, 1, 0]);
        assert_eq!(h.left_after_first, vec![1, 0, 0]);
        assert_eq!(h.categories(), vec![REENTERED, REENTERED, OUT_FOR_GOOD]);
        assert_eq!(h.counts(), (2, 2, 1));
    }

    #[test]
    fn flux_counts_the_changes_over_its_interval_only() {
        let mut h = History::new(4, (1.0, 2.0));
        let s = |p: [f64; 4]| ContactSolution {
            pressure: p.to_vec(),
            displacement: vec![0.0; 4],
            p0: 1.0,
            stats: crate::engine::contact::SolveStats {
                solver: "cg",
                iterations: 0,
                residual: Default::default(),
                wall_s: 0.0,
                warm: false,
            },
        };
        h.record(0, 1.0, &s([1.0, 0.0, 0.0, 1.0])).unwrap();
        h.record(1, 1.5, &s([0.0, 1.0, 0.0, 1.0])).unwrap();
        h.record(2, 2.0, &s([0.0, 1.0, 1.0, 1.0])).unwrap();
        h.record(3, 3.0, &s([1.0, 1.0, 1.0, 1.0])).unwrap();
        // Over (1, 2]: point 0 left, points 1 and 2 entered, point 3 stayed.
        let f = h.flux.as_ref().unwrap();
        assert_eq!(f.map, vec![3, 1, 1, 0]);
        assert_eq!((f.into, f.out_of), (0.5, 0.25));
        assert_eq!(f.into_of_noncontact, 1.0);
    }
}
