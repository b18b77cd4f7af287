//! Which points entered or left contact between two solutions of one surface (or, more
//! generally, rose above or fell below a pressure threshold): each point's change, from its
//! state before and after.
//!
//! A pressure `p` lies *above* a threshold `t` when `p > 0` and `p >= t` ([`above`]). For
//! `t = 0` that is contact, and the rest is the zero-pressure set, Persson's absorbing
//! boundary; for `t > 0` the rest is the pressure bin `[0, t)`, the lowest bin
//! `n dp <= p < (n + 1) dp` of the paper's transition analysis (section 3.2) with `dp =
//! t`. A point's change over a step is one of four ([`change`]), numbered as the colours of
//! the contact-change maps:
//!
//! * [`BOTH`] (grey): above the threshold before and after (in contact at both);
//! * [`ENTERED`] (red): below, then above (entered contact);
//! * [`NEITHER`] (white): below at both;
//! * [`LEFT`] (blue): above, then below (left contact).

/// Above the threshold before and after: in contact at both.
pub const BOTH: u8 = 0;
/// Below, then above: entered contact.
pub const ENTERED: u8 = 1;
/// Below at both: out of contact at both.
pub const NEITHER: u8 = 2;
/// Above, then below: left contact.
pub const LEFT: u8 = 3;

/// The change of a point that was above the threshold (in contact) `before` and is
/// `after`.
pub fn change(before: bool, after: bool) -> u8 {
    match (before, after) {
        (true, true) => BOTH,
        (false, true) => ENTERED,
        (false, false) => NEITHER,
        (true, false) => LEFT,
    }
}

/// Whether the pressure `p` lies above the threshold `t`: `p > 0` and `p >= t` (for
/// `t = 0`, in contact).
pub fn above(p: f64, t: f64) -> bool {
    p > 0.0 && p >= t
}

/// The change of a point across the threshold `t`, from its pressures `before` and
/// `after`.
pub fn across(before: f64, after: f64, t: f64) -> u8 {
    change(above(before, t), above(after, t))
}

/// The change of a point into or out of contact, from its pressures `before` and `after`
/// (across `t = 0`).
pub fn category(before: f64, after: f64) -> u8 {
    across(before, after, 0.0)
}

/// The change into or out of contact of every point, from the pressures `before` and
/// `after` of each (one per point at both).
pub fn categories(before: &[f64], after: &[f64]) -> Vec<u8> {
    assert_eq!(before.len(), after.len(), "one pressure per point at both");
    before
        .iter()
        .zip(after)
        .map(|(&b, &a)| category(b, a))
        .collect()
}

/// Packs 2-bit categories, four to a byte, as hex.
pub fn pack_categories(c: &[u8]) -> String {
    c.chunks(4)
        .map(|q| {
            let b = q
                .iter()
                .enumerate()
                .fold(0u8, |acc, (k, &v)| acc | ((v & 3) << (2 * k)));
            format!("{b:02x}")
        })
        .collect()
}

/// Unpacks [`pack_categories`] into `len` categories.
pub fn unpack_categories(hex: &str, len: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(len);
    for k in (0..hex.len()).step_by(2) {
        let b = u8::from_str_radix(&hex[k..k + 2], 16).unwrap_or(0);
        for j in 0..4 {
            if out.len() < len {
                out.push((b >> (2 * j)) & 3);
            }
        }
    }
    out
}

/// The colours of a map of the changes over one step, as the paper's contact-change
/// figure: grey in contact at both, red entered, white out of contact at both, blue left.
pub fn step_palette() -> Vec<([u8; 3], String)> {
    vec![
        ([150, 150, 150], "in contact at both".into()),
        ([220, 40, 40], "entered contact".into()),
        ([255, 255, 255], "out of contact at both".into()),
        ([40, 80, 220], "left contact".into()),
    ]
}

/// `|out - in| / ((out + in) / 2)`: the net flux over the mean one-way flux (0 when
/// both are 0).
pub fn net_over_gross(flux_in: f64, flux_out: f64) -> f64 {
    (flux_out - flux_in).abs() / (0.5 * (flux_out + flux_in)).max(f64::MIN_POSITIVE)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn net_over_gross_is_the_net_flux_over_the_mean_one_way_flux() {
        assert!((net_over_gross(0.00675, 0.00597) - 0.12264).abs() < 1e-5);
        assert_eq!(net_over_gross(0.0, 0.0), 0.0);
    }

    #[test]
    fn categories_pack_and_unpack() {
        let c: Vec<u8> = (0..37).map(|k| (k * 7 % 4) as u8).collect();
        assert_eq!(unpack_categories(&pack_categories(&c), c.len()), c);
    }

    #[test]
    fn the_four_changes_are_the_map_colours() {
        let states = [(true, true), (false, true), (false, false), (true, false)];
        let changes = states.map(|(b, a)| change(b, a));
        assert_eq!(changes, [BOTH, ENTERED, NEITHER, LEFT]);
        assert_eq!(changes, [0, 1, 2, 3]);
        assert_eq!(category(0.0, 1e-300), ENTERED);
        assert_eq!(category(1e-300, -0.0), LEFT);
        let before = [1.0, 0.0, 0.0, 2.0, 0.5];
        let after = [0.5, 0.1, 0.0, 0.0, 0.3];
        assert_eq!(
            categories(&before, &after),
            [BOTH, ENTERED, NEITHER, LEFT, BOTH]
        );
    }

    #[test]
    fn a_threshold_moves_the_lowest_bin_up() {
        // The bin [0, 0.4): 0.3 -> 0.5 rises out of it, 0.0 -> 0.3 stays in it, a point at
        // the threshold lies above it.
        assert_eq!(across(0.3, 0.5, 0.4), ENTERED);
        assert_eq!(across(0.0, 0.3, 0.4), NEITHER);
        assert_eq!(across(0.4, 0.39, 0.4), LEFT);
        assert_eq!(across(0.0, 0.3, 0.0), ENTERED);
        assert!(above(0.4, 0.4) && !above(0.0, 0.0) && !above(f64::NAN, 0.0));
    }
}
