//! The cases of a run: the tier's (quick ⊂ default ⊂ full) or the `--case` ids, then this
//! shard's part of them (core::shard's partition over the run times recorded in `reports/`).

use std::collections::BTreeMap;

use crate::core::case::{Case, Tier};
use crate::core::shard::{partition, Shard, UNKNOWN_SECONDS};

/// What a run runs.
#[derive(Debug)]
pub struct Selection<'a> {
    /// Every case of the run before sharding, in catalogue order.
    pub all: Vec<&'a Case>,
    /// This shard's cases, in catalogue order.
    pub mine: Vec<&'a Case>,
    /// The expected run time of each of `mine` (s): the recorded one, else UNKNOWN_SECONDS.
    pub expected: Vec<f64>,
}

/// The cases of tier `tier`, or the cases named by `ids` (any tier) when some are given; then
/// shard `shard` of them. An unknown id is an error naming it.
pub fn select<'a>(
    cases: &'a [Case],
    tier: Tier,
    ids: &[String],
    shard: Shard,
    recorded: &BTreeMap<String, f64>,
) -> Result<Selection<'a>, String> {
    for id in ids {
        if !cases.iter().any(|c| &c.header.id == id) {
            return Err(format!("no case `{id}` (see `verify --list`)"));
        }
    }
    let all: Vec<&Case> = cases
        .iter()
        .filter(|c| {
            if ids.is_empty() {
                c.header.tier.runs_in(tier)
            } else {
                ids.contains(&c.header.id)
            }
        })
        .collect();
    let seconds = |c: &Case| {
        recorded
            .get(&c.header.id)
            .copied()
            .unwrap_or(UNKNOWN_SECONDS)
    };
    let timed: Vec<(String, f64)> = all
        .iter()
        .map(|c| (c.header.id.clone(), seconds(c)))
        .collect();
    let shard_of = partition(&timed, shard.count);
    let mine: Vec<&Case> = all
        .iter()
        .zip(&shard_of)
        .filter(|(_, &s)| s + 1 == shard.index)
        .map(|(c, _)| *c)
        .collect();
    let expected = mine.iter().map(|c| seconds(c)).collect();
    Ok(Selection {
        all,
        mine,
        expected,
    })
}

#[cfg(test)]
mod tests {
    //! Selection: the tiers nest; the shards of a selection cover it exactly once.
    use super::*;
    use std::path::Path;

    fn case(id: &str, tier: &str) -> Case {
        Case::from_text(
            Path::new(&format!("{id}.toml")),
            &format!(
                "id = \"{id}\"\ntitle = \"t\"\nkind = \"k\"\ntier = \"{tier}\"\nexplanation = \"e\""
            ),
        )
        .expect("a header")
    }

    #[test]
    fn tiers_nest_and_shards_cover_the_selection_once() {
        let cases = vec![
            case("a", "quick"),
            case("b", "default"),
            case("c", "full"),
            case("d", "quick"),
        ];
        let none = BTreeMap::new();
        let ids =
            |s: &Selection| -> Vec<String> { s.mine.iter().map(|c| c.header.id.clone()).collect() };
        let q = select(&cases, Tier::Quick, &[], Shard::WHOLE, &none).expect("quick");
        assert_eq!(ids(&q), ["a", "d"]);
        let d = select(&cases, Tier::Default, &[], Shard::WHOLE, &none).expect("default");
        assert_eq!(ids(&d), ["a", "b", "d"]);
        let f = select(&cases, Tier::Full, &[], Shard::WHOLE, &none).expect("full");
        assert_eq!(f.all.len(), 4);
        let mut union: Vec<String> = (1..=3)
            .flat_map(|i| {
                let s = select(&cases, Tier::Full, &[], Shard { index: i, count: 3 }, &none)
                    .expect("shard");
                assert_eq!(s.all.len(), 4);
                ids(&s)
            })
            .collect();
        union.sort();
        assert_eq!(union, ["a", "b", "c", "d"]);
        let e = select(&cases, Tier::Quick, &["zz".into()], Shard::WHOLE, &none)
            .expect_err("unknown id");
        assert!(e.contains("zz"));
    }
}
