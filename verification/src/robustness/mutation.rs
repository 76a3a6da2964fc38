//! Scene mutations as a careless or hostile user would make them: a key deleted or misspelt, a
//! value of the wrong type, zero, negative, huge, tiny, subnormal or non-finite numbers, absurd
//! counts, malformed or enormous expressions, arrays with an element too many or too few.
//!
//! Deterministic: the scene of (seed, base, index) is always the same, so every finding is
//! reproduced from those three numbers (`Mutation::describe` says what was changed).

use toml::Value;

/// SplitMix64: a small, fast, well-mixed generator (Steele, Lea & Flood 2014) — enough to pick
/// mutations; no statistical claim rests on it.
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    /// The generator of scene `index` of base `base` in the campaign `seed`.
    pub fn for_scene(seed: u64, base: usize, index: usize) -> Self {
        let mut r = Rng(seed ^ 0x9E37_79B9_7F4A_7C15);
        r.0 ^= (base as u64).wrapping_mul(0xD1B5_4A32_D192_ED03);
        r.next_u64();
        r.0 ^= (index as u64).wrapping_mul(0x94D0_49BB_1331_11EB);
        r.next_u64();
        r
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in 0..n (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// One step of a path into a TOML document.
#[derive(Debug, Clone, PartialEq)]
pub enum Step {
    Key(String),
    Index(usize),
}

/// A path written as the user would (`sweep[0].points`).
pub fn path_text(path: &[Step]) -> String {
    let mut s = String::new();
    for step in path {
        match step {
            Step::Key(k) => {
                if !s.is_empty() {
                    s.push('.');
                }
                s.push_str(k);
            }
            Step::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

/// Parses `a.b[2].c` into steps.
pub fn parse_path(text: &str) -> Vec<Step> {
    let mut out = Vec::new();
    for part in text.split('.') {
        let (key, rest) = part.split_once('[').unwrap_or((part, ""));
        if !key.is_empty() {
            out.push(Step::Key(key.to_string()));
        }
        for idx in rest.split('[') {
            if let Ok(i) = idx.trim_end_matches(']').parse() {
                out.push(Step::Index(i));
            }
        }
    }
    out
}

/// The value at `path`, if any.
pub fn get_mut<'a>(root: &'a mut Value, path: &[Step]) -> Option<&'a mut Value> {
    let mut v = root;
    for step in path {
        v = match (step, v) {
            (Step::Key(k), Value::Table(t)) => t.get_mut(k)?,
            (Step::Index(i), Value::Array(a)) => a.get_mut(*i)?,
            _ => return None,
        };
    }
    Some(v)
}

/// Every leaf (a value that is not a table or an array of tables) with its path.
fn leaves(v: &Value, path: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    match v {
        Value::Table(t) => {
            for (k, child) in t {
                path.push(Step::Key(k.clone()));
                leaves(child, path, out);
                path.pop();
            }
        }
        Value::Array(a) if a.iter().any(|x| x.is_table()) => {
            for (i, child) in a.iter().enumerate() {
                path.push(Step::Index(i));
                leaves(child, path, out);
                path.pop();
            }
        }
        _ => out.push(path.clone()),
    }
}

/// What a mutation did, for the report.
#[derive(Debug, Clone)]
pub struct Mutation {
    /// The key as the user would write it (`time.steps`).
    pub key: String,
    pub what: String,
}

impl Mutation {
    pub fn describe(&self) -> String {
        format!("{}: {}", self.key, self.what)
    }
}

const NUMBERS: [f64; 16] = [
    0.0,
    -1.0,
    1e308,
    -1e308,
    1e300,
    1e-300,
    1e-308,
    5e-324,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e150,
    1e-150,
    0.5,
    1e6,
    -1e-9,
];

const INTEGERS: [i64; 10] = [
    0,
    -1,
    -5,
    1,
    2,
    i64::MAX,
    i64::MIN,
    1_000_000_000,
    100_000,
    1 << 40,
];

const EXPRESSIONS: [&str; 16] = [
    "x+",
    "((((",
    "sin(",
    "1/0",
    "ln(-t)",
    "sqrt(-1)",
    "t*1e308*1e308",
    "exp(1000)",
    "nan",
    "",
    "foo(x)",
    "x y",
    "0/0",
    "1e400",
    "-t",
    "2^2^2^2^2^2",
];

/// The mutated value for a leaf `v` (its new value and a description).
fn mutate_value(v: &Value, rng: &mut Rng) -> (Option<Value>, String) {
    let choice = rng.below(10);
    match choice {
        0 => (None, "deleted".into()),
        1 => {
            let alternatives = [
                Value::String("abc".into()),
                Value::Float(1.0),
                Value::Integer(3),
                Value::Boolean(true),
                Value::Array(vec![
                    Value::Float(1.0),
                    Value::Float(2.0),
                    Value::Float(3.0),
                ]),
                Value::Table(toml::Table::new()),
                Value::Array(vec![]),
            ];
            let new = rng.pick(&alternatives).clone();
            let text = format!("replaced by {new} (another type)");
            (Some(new), text)
        }
        _ => match v {
            Value::Float(_) | Value::Integer(_) => {
                if rng.below(2) == 0 {
                    let x = *rng.pick(&INTEGERS);
                    (Some(Value::Integer(x)), format!("= {x}"))
                } else {
                    let x = *rng.pick(&NUMBERS);
                    let scaled = match (rng.below(3), v) {
                        (0, Value::Float(f)) => f * 1e6,
                        (1, Value::Float(f)) => f * 1e-6,
                        _ => x,
                    };
                    (Some(Value::Float(scaled)), format!("= {scaled:e}"))
                }
            }
            Value::String(s) => {
                if rng.below(4) == 0 {
                    // a long expression (the campaign of the issue: 50 000 terms)
                    let n = [100usize, 2000, 50_000][rng.below(3)];
                    let long = vec!["x"; n].join("+");
                    (Some(Value::String(long)), format!("= x+x+… ({n} terms)"))
                } else if rng.below(3) == 0 {
                    let new = format!("{s}{s}");
                    (Some(Value::String(new.clone())), format!("= {new:?}"))
                } else {
                    let e = rng.pick(&EXPRESSIONS);
                    (Some(Value::String(e.to_string())), format!("= {e:?}"))
                }
            }
            Value::Array(a) => {
                let mut a = a.clone();
                match rng.below(4) {
                    0 => {
                        a.push(a.last().cloned().unwrap_or(Value::Float(99.0)));
                        (Some(Value::Array(a)), "one element more".into())
                    }
                    1 => {
                        a.pop();
                        (Some(Value::Array(a)), "one element fewer".into())
                    }
                    2 => (Some(Value::Array(vec![])), "= []".into()),
                    _ => {
                        if let Some(first) = a.first_mut() {
                            let (new, what) = mutate_value(first, rng);
                            if let Some(n) = new {
                                *first = n;
                            }
                            (Some(Value::Array(a)), format!("[0] {what}"))
                        } else {
                            (Some(Value::Array(a)), "unchanged".into())
                        }
                    }
                }
            }
            Value::Boolean(b) => (Some(Value::Boolean(!b)), format!("= {}", !b)),
            _ => (Some(Value::String("x".into())), "= \"x\"".into()),
        },
    }
}

/// Every path to an array of tables (`body`, `contact_pair`, `sweep`, …).
fn table_arrays(v: &Value, path: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    match v {
        Value::Table(t) => {
            for (k, x) in t {
                path.push(Step::Key(k.clone()));
                table_arrays(x, path, out);
                path.pop();
            }
        }
        Value::Array(a) if !a.is_empty() && a.iter().all(Value::is_table) => {
            out.push(path.clone());
            for (i, x) in a.iter().enumerate() {
                path.push(Step::Index(i));
                table_arrays(x, path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

/// Every path to a table with at least two numbers among its own keys (a plate's radii, a
/// range's ends), with those keys.
fn number_pairs(v: &Value, path: &mut Vec<Step>, out: &mut Vec<(Vec<Step>, Vec<String>)>) {
    match v {
        Value::Table(t) => {
            let numbers: Vec<String> = t
                .iter()
                .filter(|(_, x)| x.is_float() || x.is_integer())
                .map(|(k, _)| k.clone())
                .collect();
            if numbers.len() >= 2 {
                out.push((path.clone(), numbers));
            }
            for (k, x) in t {
                path.push(Step::Key(k.clone()));
                number_pairs(x, path, out);
                path.pop();
            }
        }
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                path.push(Step::Index(i));
                number_pairs(x, path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

/// A mutation of the scene's structure, as the multi-body and mesh scenes invite: a table of an
/// array repeated (a duplicate body, pair or region: the same name twice, two bodies in one
/// place) or dropped (a pair naming a body that is gone), two numbers of one table exchanged (a
/// plate's inner radius above its outer one, a range run backwards), or one name written where
/// another belongs (a pair's master = its slave, a group name of another body). None when the
/// scene has nothing of the kind drawn.
fn mutate_structure(scene: &mut Value, rng: &mut Rng) -> Vec<Mutation> {
    match rng.below(3) {
        0 => {
            let mut arrays = Vec::new();
            table_arrays(scene, &mut Vec::new(), &mut arrays);
            if arrays.is_empty() {
                return Vec::new();
            }
            let path = rng.pick(&arrays).clone();
            let repeat = rng.below(2) == 0;
            let Some(Value::Array(a)) = get_mut(scene, &path) else {
                return Vec::new();
            };
            let i = rng.below(a.len());
            let what = if repeat {
                let copy = a[i].clone();
                a.push(copy);
                format!("[{i}] repeated as [{}]", a.len() - 1)
            } else {
                a.remove(i);
                format!("[{i}] dropped")
            };
            vec![Mutation {
                key: path_text(&path),
                what,
            }]
        }
        1 => {
            let mut tables = Vec::new();
            number_pairs(scene, &mut Vec::new(), &mut tables);
            if tables.is_empty() {
                return Vec::new();
            }
            let (path, keys) = rng.pick(&tables).clone();
            let i = rng.below(keys.len());
            let j = (i + 1 + rng.below(keys.len() - 1)) % keys.len();
            let Some(Value::Table(t)) = get_mut(scene, &path) else {
                return Vec::new();
            };
            let (a, b) = (t[&keys[i]].clone(), t[&keys[j]].clone());
            t.insert(keys[i].clone(), b);
            t.insert(keys[j].clone(), a);
            let at = |k: &String| {
                let mut p = path.clone();
                p.push(Step::Key(k.clone()));
                path_text(&p)
            };
            let (ki, kj) = (at(&keys[i]), at(&keys[j]));
            vec![
                Mutation {
                    key: ki.clone(),
                    what: format!("exchanged with {kj}"),
                },
                Mutation {
                    key: kj,
                    what: format!("exchanged with {ki}"),
                },
            ]
        }
        _ => {
            let mut paths = Vec::new();
            leaves(scene, &mut Vec::new(), &mut paths);
            let strings: Vec<Vec<Step>> = paths
                .into_iter()
                .filter(|p| {
                    get_mut(scene, p).is_some_and(|v| v.is_str())
                        && !matches!(p.first(), Some(Step::Key(k)) if k == "model" || k == "title")
                })
                .collect();
            if strings.len() < 2 {
                return Vec::new();
            }
            let from = rng.pick(&strings).clone();
            let Some(value) = get_mut(scene, &from).cloned() else {
                return Vec::new();
            };
            // a name written where another one was: only slots that held something else
            let others: Vec<Vec<Step>> = strings
                .into_iter()
                .filter(|p| get_mut(scene, p).is_some_and(|v| *v != value))
                .collect();
            if others.is_empty() {
                return Vec::new();
            }
            let to = rng.pick(&others).clone();
            let Some(slot) = get_mut(scene, &to) else {
                return Vec::new();
            };
            *slot = value.clone();
            vec![Mutation {
                key: path_text(&to),
                what: format!("= {value} (the value of {})", path_text(&from)),
            }]
        }
    }
}

/// A file's bytes mutated as a careless user or a broken disk would leave them: cut short,
/// binary garbage written over 64 bytes, a line repeated or dropped, a number replaced by one
/// that is not (`nan`, `1e400`) or out of place (`-1`, `0`, `99999999999`).
pub fn mutate_file(bytes: &[u8], rng: &mut Rng) -> (Vec<u8>, String) {
    let mut b = bytes.to_vec();
    if b.is_empty() {
        return (b, "empty".into());
    }
    let lines: Vec<(usize, usize)> = {
        let mut out = Vec::new();
        let mut start = 0;
        for (i, &c) in b.iter().enumerate() {
            if c == b'\n' {
                out.push((start, i + 1));
                start = i + 1;
            }
        }
        if start < b.len() {
            out.push((start, b.len()));
        }
        out
    };
    match rng.below(5) {
        0 => {
            let at = rng.below(b.len());
            b.truncate(at);
            (b, format!("cut at byte {at} of {}", bytes.len()))
        }
        1 => {
            let at = rng.below(b.len());
            for x in b.iter_mut().skip(at).take(64) {
                *x = (rng.next_u64() & 0xff) as u8;
            }
            (b, format!("64 bytes of binary garbage from byte {at}"))
        }
        2 => {
            let (s, e) = *rng.pick(&lines);
            let line = b[s..e].to_vec();
            b.splice(e..e, line);
            (b, format!("a line repeated (bytes {s}–{e})"))
        }
        3 => {
            let (s, e) = *rng.pick(&lines);
            b.drain(s..e);
            (b, format!("a line dropped (bytes {s}–{e})"))
        }
        _ => {
            let numbers: Vec<(usize, usize)> = {
                let mut out = Vec::new();
                let mut i = 0;
                while i < b.len() {
                    if b[i].is_ascii_digit() && (i == 0 || b[i - 1].is_ascii_whitespace()) {
                        let s = i;
                        while i < b.len() && !b[i].is_ascii_whitespace() {
                            i += 1;
                        }
                        out.push((s, i));
                    }
                    i += 1;
                }
                out
            };
            if numbers.is_empty() {
                return (b, "unchanged (no number)".into());
            }
            let (s, e) = *rng.pick(&numbers);
            let choices: Vec<&str> = ["nan", "1e400", "-1", "0", "99999999999"]
                .into_iter()
                .filter(|c| c.as_bytes() != &b[s..e])
                .collect();
            let new = *rng.pick(&choices);
            b.splice(s..e, new.bytes());
            (b, format!("the number at byte {s} replaced by {new}"))
        }
    }
}

/// Applies 1 or 2 mutations to `scene` (a whole scene document); now and then one of them is a
/// mutation of its structure ([`mutate_structure`]).
pub fn mutate(scene: &mut Value, rng: &mut Rng) -> Vec<Mutation> {
    let mut out = Vec::new();
    let count = 1 + rng.below(2);
    for _ in 0..count {
        if rng.below(6) == 0 {
            let structural = mutate_structure(scene, rng);
            if !structural.is_empty() {
                out.extend(structural);
                continue;
            }
        }
        let mut paths = Vec::new();
        leaves(scene, &mut Vec::new(), &mut paths);
        if paths.is_empty() {
            break;
        }
        let path = rng.pick(&paths).clone();
        let key = path_text(&path);
        // a misspelt key now and then: the value moves to a key the scene does not know
        if rng.below(12) == 0 {
            if let (Some(Step::Key(last)), Some(parent)) = (
                path.last().cloned(),
                get_mut(scene, &path[..path.len() - 1]),
            ) {
                if let Some(t) = parent.as_table_mut() {
                    if let Some(v) = t.remove(&last) {
                        let wrong = format!("{last}s");
                        t.insert(wrong.clone(), v);
                        out.push(Mutation {
                            key: key.clone(),
                            what: format!("misspelt as {wrong}"),
                        });
                        continue;
                    }
                }
            }
        }
        let Some(slot) = get_mut(scene, &path) else {
            continue;
        };
        let (new, what) = mutate_value(slot, rng);
        match new {
            Some(v) => *slot = v,
            None => {
                let parent = get_mut(scene, &path[..path.len() - 1]);
                match (parent, path.last()) {
                    (Some(Value::Table(t)), Some(Step::Key(k))) => {
                        t.remove(k);
                    }
                    (Some(Value::Array(a)), Some(Step::Index(i))) if *i < a.len() => {
                        a.remove(*i);
                    }
                    _ => {}
                }
            }
        }
        out.push(Mutation { key, what });
    }
    out
}

#[cfg(test)]
mod tests {
    //! Mutations are reproducible from (seed, base, index) and change the scene.
    use super::*;

    #[test]
    fn the_same_numbers_give_the_same_mutations() {
        let base: Value = toml::from_str::<toml::Table>(
            "model = \"rod\"\n[time]\nsteps = 10\n[[sweep]]\npoints = 3\nfrom = 0.1\n",
        )
        .map(Value::Table)
        .unwrap();
        for index in 0..50 {
            let (mut a, mut b) = (base.clone(), base.clone());
            let ma = mutate(&mut a, &mut Rng::for_scene(7, 0, index));
            let mb = mutate(&mut b, &mut Rng::for_scene(7, 0, index));
            // (NaN ≠ NaN as a value: compare the text)
            assert_eq!(a.to_string(), b.to_string());
            assert_eq!(
                ma.iter().map(Mutation::describe).collect::<Vec<_>>(),
                mb.iter().map(Mutation::describe).collect::<Vec<_>>()
            );
            assert!(!ma.is_empty());
        }
        assert_eq!(path_text(&parse_path("sweep[0].points")), "sweep[0].points");
    }

    fn bodies() -> Value {
        toml::from_str::<toml::Table>(
            "model = \"multibody\"\n[[body]]\nname = \"a\"\n[body.shape]\ninner_radius = 0.2\nouter_radius = 1.0\n\
             [[body]]\nname = \"b\"\n[[contact_pair]]\nslave = \"a\"\nmaster = \"b\"\n",
        )
        .map(Value::Table)
        .unwrap()
    }

    #[test]
    fn structural_mutations_repeat_drop_exchange_and_cross_names() {
        // over many draws every kind appears on a scene of bodies and pairs, and each changes it
        let mut seen = [false; 4];
        for index in 0..400 {
            let mut doc = bodies();
            let ms = mutate_structure(&mut doc, &mut Rng::for_scene(3, 0, index));
            if ms.is_empty() {
                continue;
            }
            assert_ne!(doc.to_string(), bodies().to_string(), "{ms:?}");
            let what = &ms[0].what;
            seen[0] |= what.contains("repeated");
            seen[1] |= what.contains("dropped");
            seen[2] |= what.contains("exchanged with body[0].shape.");
            seen[3] |= what.contains("(the value of");
        }
        assert_eq!(seen, [true; 4]);
        // the plate's radii exchanged: inner above outer
        let mut doc = bodies();
        let mut rng = Rng::for_scene(3, 0, 0);
        let mut found = false;
        for _ in 0..200 {
            let ms = mutate_structure(&mut doc, &mut rng);
            if ms.len() == 2 {
                let shape = &doc["body"][0]["shape"];
                found = shape["inner_radius"].as_float() == Some(1.0)
                    && shape["outer_radius"].as_float() == Some(0.2);
                break;
            }
            doc = bodies();
        }
        assert!(found);
    }

    #[test]
    fn file_mutations_cut_garble_repeat_drop_and_replace_numbers() {
        let mesh = b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n";
        let mut kinds = std::collections::BTreeSet::new();
        for index in 0..200 {
            let mut rng = Rng::for_scene(5, 1, index);
            let (a, what) = mutate_file(mesh, &mut rng);
            let (b, again) = mutate_file(mesh, &mut Rng::for_scene(5, 1, index));
            assert_eq!((a.clone(), what.clone()), (b, again), "reproducible");
            if !what.starts_with("64 bytes") {
                // garbage may happen to rewrite a byte with itself; every other kind changes it
                assert_ne!(a.as_slice(), mesh.as_slice(), "{what}");
            }
            kinds.insert(
                what.split_whitespace()
                    .take(2)
                    .collect::<Vec<_>>()
                    .join(" "),
            );
        }
        for k in ["cut at", "64 bytes", "a line", "the number"] {
            assert!(kinds.iter().any(|x| x.starts_with(k)), "{k} in {kinds:?}");
        }
    }
}
