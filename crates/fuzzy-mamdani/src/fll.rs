//! fuzzylite's `.fll` format (fuzzylite 6 – 8), read and written.
//!
//! An imported engine evaluates as pyfuzzylite 8 does: `lock-range: true` clamps inputs,
//! `false` evaluates them where they are; `Centroid N` (etc.) integrates with `N` midpoints
//! ([`Resolution::Midpoints`], 1000 when `N` is omitted); hedges apply as fuzzylite applies
//! them, in conclusions to the activation degree; `default: nan` means no default.
//! `conjunction: none` (and the other operators) is accepted where no rule needs the
//! operator. `CenterAverage` is an extension of this crate (fuzzylite has none).
//!
//! Output variables in antecedents (chained engines) read the conclusions so far as fuzzylite
//! does ([`crate::Expr::Output`]).
//!
//! What fuzzylite has and this crate does not is a typed [`FileError::Unsupported`] naming the
//! feature and its line: an output with `aggregation: none` read in an antecedent, the terms `Arc` and
//! `SemiEllipse` (pyfuzzylite only) and Takagi–Sugeno's `Constant`, `Linear`, `Function`,
//! weighted defuzzifiers (Takagi–Sugeno / Tsukamoto), term heights other than 1,
//! `lock-previous`, output `lock-range`, disabled variables and blocks.

use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

use crate::format::{
    FileError, at_column, at_line_start, numbers, rule_error, syntax, unsupported,
};
use crate::{
    Activation, Comparison, Defuzzifier, Engine, EngineBuilder, Expr, InputVariable, Mf,
    OutOfRange, OutputVariable, Real, Resolution, Rule, SNorm, TNorm, Term, parse_rule, rule_text,
};

const TNORMS: [(&str, TNorm); 7] = [
    ("Minimum", TNorm::Minimum),
    ("AlgebraicProduct", TNorm::AlgebraicProduct),
    ("BoundedDifference", TNorm::BoundedDifference),
    ("DrasticProduct", TNorm::DrasticProduct),
    ("EinsteinProduct", TNorm::EinsteinProduct),
    ("HamacherProduct", TNorm::HamacherProduct),
    ("NilpotentMinimum", TNorm::NilpotentMinimum),
];
const SNORMS: [(&str, SNorm); 9] = [
    ("Maximum", SNorm::Maximum),
    ("AlgebraicSum", SNorm::AlgebraicSum),
    ("BoundedSum", SNorm::BoundedSum),
    ("DrasticSum", SNorm::DrasticSum),
    ("EinsteinSum", SNorm::EinsteinSum),
    ("HamacherSum", SNorm::HamacherSum),
    ("UnboundedSum", SNorm::UnboundedSum),
    ("NilpotentMaximum", SNorm::NilpotentMaximum),
    ("NormalizedSum", SNorm::NormalizedSum),
];

/// fuzzylite's resolution when a file gives none (pyfuzzylite 8's default).
const DEFAULT_RESOLUTION: usize = 1000;

/// The comment [`to_fll`] puts after a defuzzifier sampled MATLAB's way
/// ([`Resolution::Samples`]): fuzzylite ignores it (and integrates midpoints), [`from_fll`]
/// reads it back to the same engine.
const SAMPLES_MARKER: &str = "# fuzzy-mamdani: end-point samples";

fn end_point_samples(d: Defuzzifier) -> Defuzzifier {
    let s = |r: Resolution| match r {
        Resolution::Midpoints(n) => Resolution::Samples(n),
        r => r,
    };
    match d {
        Defuzzifier::Centroid(r) => Defuzzifier::Centroid(s(r)),
        Defuzzifier::Bisector(r) => Defuzzifier::Bisector(s(r)),
        Defuzzifier::MeanOfMaximum(r) => Defuzzifier::MeanOfMaximum(s(r)),
        Defuzzifier::SmallestOfMaximum(r) => Defuzzifier::SmallestOfMaximum(s(r)),
        Defuzzifier::LargestOfMaximum(r) => Defuzzifier::LargestOfMaximum(s(r)),
        d => d,
    }
}

enum Section {
    None,
    Input,
    Output,
    Rules,
}

/// Reads an engine from `.fll` text.
///
/// ```
/// use fuzzy_mamdani::{FileError, from_fll};
/// let fll = "Engine: e\nInputVariable: x\n  range: 0 1\n  term: lo Triangle 0 0 1\n\
///            OutputVariable: y\n  range: 0 1\n  defuzzifier: Centroid 100\n  term: t Triangle 0 1 1\n\
///            RuleBlock: r\n  conjunction: none\n  implication: Minimum\n\
///            rule: if x is very lo then y is t\n";
/// let engine = from_fll::<f64>(fll)?;
/// assert_eq!(engine.rules().len(), 1);
/// // fuzzylite's default implication is none: a rule concluding on a centroid then cannot be
/// // evaluated, by fuzzylite either.
/// let err = from_fll::<f64>(&fll.replace("implication: Minimum", "")).unwrap_err();
/// assert!(matches!(err, FileError::MissingOperator { line: 12, operator: "implication", .. }));
/// let err = from_fll::<f64>("Engine: e\nInputVariable: x\n  range: 0 one\n").unwrap_err();
/// assert_eq!(err.to_string(), "line 3, column 10: `one` is not a number");
/// let err = from_fll::<f64>(&fll.replace("very lo", "awfully lo")).unwrap_err();
/// assert_eq!(err.to_string(), "line 12: unknown hedge `awfully`");
/// # Ok::<(), FileError>(())
/// ```
pub fn from_fll<T: Real>(text: &str) -> Result<Engine<T>, FileError> {
    read_fll(text).map_err(|e| at_line_start(e, text))
}

/// A rule block as read: its operators (`None` for `none`), activation and first rule.
struct Block<T> {
    name: String,
    conjunction: Option<TNorm>,
    disjunction: Option<SNorm>,
    implication: Option<TNorm>,
    activation: Activation<T>,
    first_rule: usize,
}

fn read_fll<T: Real>(text: &str) -> Result<Engine<T>, FileError> {
    let mut name = String::new();
    let (mut inputs, mut outputs, mut rules) = (
        Vec::new(),
        Vec::<OutputVariable<T>>::new(),
        Vec::<Rule<T>>::new(),
    );
    let mut blocks: Vec<Block<T>> = Vec::new();
    let (mut aggregation_none, mut rule_lines) = (Vec::new(), Vec::new());
    let mut section = Section::None;
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let content = raw.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let (key, value) = content
            .split_once(':')
            .ok_or_else(|| syntax(line, "expected `key: value`"))?;
        let value = value.trim();
        // 1-based column of the value in the raw line (errors point into it).
        let column = raw.find(':').map_or(1, |k| {
            let after = &raw[k + 1..];
            raw[..k + 1].chars().count()
                + after.chars().take_while(|c| c.is_whitespace()).count()
                + 1
        });
        let at = |e: FileError| at_column(e, column);
        match (key.trim(), &section) {
            ("Engine", _) => name = value.to_string(),
            ("description", _) => {}
            ("InputVariable", _) => {
                section = Section::Input;
                inputs.push(InputVariable {
                    name: value.to_string(),
                    min: T::zero(),
                    max: T::one(),
                    terms: Vec::new(),
                    out_of_range: OutOfRange::Evaluate,
                });
            }
            ("OutputVariable", _) => {
                section = Section::Output;
                outputs.push(OutputVariable {
                    name: value.to_string(),
                    min: T::zero(),
                    max: T::one(),
                    terms: Vec::new(),
                    aggregation: SNorm::Maximum,
                    defuzzifier: Defuzzifier::Centroid(Resolution::Midpoints(DEFAULT_RESOLUTION)),
                    default: None,
                });
            }
            ("RuleBlock", _) => {
                // fuzzylite's defaults for a block that names no operator: none at all.
                blocks.push(Block {
                    name: value.to_string(),
                    conjunction: None,
                    disjunction: None,
                    implication: None,
                    activation: Activation::General,
                    first_rule: rules.len(),
                });
                section = Section::Rules
            }
            ("enabled", _) if value == "true" => {}
            ("enabled", _) => {
                return Err(unsupported(line, format!("`enabled: {value}`")));
            }
            ("range", Section::Input) => {
                (last(&mut inputs, line)?.min, last(&mut inputs, line)?.max) =
                    range(value, line).map_err(at)?
            }
            ("range", Section::Output) => {
                (last(&mut outputs, line)?.min, last(&mut outputs, line)?.max) =
                    range(value, line).map_err(at)?
            }
            ("lock-range", Section::Input) => {
                last(&mut inputs, line)?.out_of_range = if value == "true" {
                    OutOfRange::Clamp
                } else {
                    OutOfRange::Evaluate
                };
            }
            ("lock-range" | "lock-previous" | "lock-valid", Section::Output)
                if value == "false" => {}
            ("lock-range" | "lock-previous" | "lock-valid", Section::Output) => {
                return Err(unsupported(
                    line,
                    format!("output `{}: {value}`", key.trim()),
                ));
            }
            ("term", Section::Input) => {
                let t = term(value, line).map_err(at)?;
                last(&mut inputs, line)?.terms.push(t)
            }
            ("term", Section::Output) => {
                let t = term(value, line).map_err(at)?;
                last(&mut outputs, line)?.terms.push(t)
            }
            ("aggregation", Section::Output) => {
                let agg = lookup(&SNORMS, value, line).map_err(at)?;
                let n = outputs.len();
                if agg.is_none() {
                    aggregation_none.push((n.saturating_sub(1), line));
                }
                last(&mut outputs, line)?.aggregation = agg.unwrap_or(SNorm::Maximum);
            }
            ("defuzzifier", Section::Output) => {
                let mut d = defuzzifier(value, line).map_err(at)?;
                if raw.contains(SAMPLES_MARKER) {
                    d = end_point_samples(d);
                }
                last(&mut outputs, line)?.defuzzifier = d;
            }
            ("default", Section::Output) => {
                let v: f64 = value
                    .parse()
                    .map_err(|_| at(syntax(line, format!("`{value}` is not a number"))))?;
                last(&mut outputs, line)?.default = v.is_finite().then(|| T::of(v));
            }
            ("conjunction", Section::Rules) => {
                last(&mut blocks, line)?.conjunction = lookup(&TNORMS, value, line).map_err(at)?
            }
            ("disjunction", Section::Rules) => {
                last(&mut blocks, line)?.disjunction = lookup(&SNORMS, value, line).map_err(at)?
            }
            ("implication", Section::Rules) => {
                last(&mut blocks, line)?.implication = lookup(&TNORMS, value, line).map_err(at)?
            }
            ("activation", Section::Rules) => {
                last(&mut blocks, line)?.activation = activation_of(value, line).map_err(at)?
            }
            ("rule", Section::Rules) => {
                let mut rule = parse_rule(value, rules.len(), &inputs, &outputs)
                    .map_err(|e| rule_error(e, line, column))?;
                carry_hedges(&mut rule.consequents, line)?;
                check_operators(&rule.antecedent, last(&mut blocks, line)?, line)?;
                rules.push(rule);
                rule_lines.push(line);
            }
            (k, _) => return Err(syntax(line, format!("unexpected `{k}` here"))),
        }
    }
    // An operator a rule would need but the file leaves `none` is an engine that cannot
    // answer (pyfuzzylite raises on the first evaluation): refused here, with its line.
    for (o, line) in aggregation_none {
        let needs = outputs[o].defuzzifier != Defuzzifier::CenterAverage
            && rules
                .iter()
                .any(|r| r.consequents.iter().any(|c| c.output == o));
        if needs {
            return Err(missing(line, "aggregation", &outputs[o].name));
        }
        // fuzzylite groups such an output's terms by unbounded sum when a rule reads it.
        if let Some(r) = rules
            .iter()
            .position(|r| r.antecedent.reads_output_where(&|x| x == o))
        {
            return Err(unsupported(
                rule_lines[r],
                format!(
                    "output variable `{}` (aggregation none) in an antecedent",
                    outputs[o].name
                ),
            ));
        }
    }
    let integral = |o: usize| outputs[o].defuzzifier.is_integral();
    for (k, block) in blocks.iter().enumerate() {
        let end = blocks.get(k + 1).map_or(rules.len(), |n| n.first_rule);
        if block.implication.is_none() {
            let first = rules[block.first_rule..end]
                .iter()
                .position(|r| r.consequents.iter().any(|c| integral(c.output)));
            if let Some(r) = first {
                return Err(missing(
                    rule_lines[block.first_rule + r],
                    "implication",
                    "a conclusion on an integral defuzzifier",
                ));
            }
        }
    }
    let mut b = EngineBuilder::new(name);
    for v in inputs {
        b = b.input_variable(v);
    }
    for v in outputs {
        b = b.output_variable(v);
    }
    let mut rules = rules.into_iter();
    for (k, block) in blocks.iter().enumerate() {
        if k > 0 {
            b = b.rule_block(block.name.clone());
        }
        // An operator no rule uses is never evaluated: any value stands in for `none`.
        b = b
            .conjunction(block.conjunction.unwrap_or(TNorm::Minimum))
            .disjunction(block.disjunction.unwrap_or(SNorm::Maximum))
            .implication(block.implication.unwrap_or(TNorm::Minimum))
            .activation(block.activation);
        let end = blocks.get(k + 1).map_or(usize::MAX, |n| n.first_rule);
        for r in rules.by_ref().take(end - block.first_rule) {
            b = b.rule_struct(r);
        }
    }
    Ok(b.build()?)
}

fn last<V>(v: &mut [V], line: usize) -> Result<&mut V, FileError> {
    v.last_mut()
        .ok_or_else(|| syntax(line, "no variable to apply this to"))
}

fn range<T: Real>(value: &str, line: usize) -> Result<(T, T), FileError> {
    match numbers(value, line)?[..] {
        [a, b] => Ok((T::of(a), T::of(b))),
        _ => Err(syntax(line, "a range is two numbers")),
    }
}

/// The norm called `value`, `None` for `none` (or an empty value).
fn lookup<N: Copy>(table: &[(&str, N)], value: &str, line: usize) -> Result<Option<N>, FileError> {
    if matches!(value, "" | "none") {
        return Ok(None);
    }
    table
        .iter()
        .find(|(n, _)| *n == value)
        .map(|(_, v)| Some(*v))
        .ok_or_else(|| syntax(line, format!("unknown norm `{value}`")))
}

/// fuzzylite applies a conclusion's hedges to the degree it then passes on to the next
/// conclusion of the same rule (`Consequent::modify` updates one variable in its loop), so
/// `then y is not A and z is B` implies `B` with `1 − w` too: reproduced for files.
fn carry_hedges(consequents: &mut [crate::Consequent], line: usize) -> Result<(), FileError> {
    let mut carried: Vec<crate::Hedge> = Vec::new();
    for c in consequents {
        // Written left to right, applied right to left: this conclusion's own go first.
        let own: Vec<crate::Hedge> = c.hedges.iter().collect();
        carried.splice(0..0, own);
        c.hedges = crate::Hedges::new(&carried)
            .ok_or_else(|| unsupported(line, "more than 10 hedges over one rule's conclusions"))?;
    }
    Ok(())
}

/// The inverse of [`carry_hedges`]: each conclusion's own hedges, which fuzzylite carries on.
fn uncarry_hedges<T: Real>(rule: &Rule<T>) -> Result<Rule<T>, FileError> {
    let mut own = rule.clone();
    let mut before: Vec<crate::Hedge> = Vec::new();
    for c in &mut own.consequents {
        let all: Vec<crate::Hedge> = c.hedges.iter().collect();
        let mine = all
            .len()
            .checked_sub(before.len())
            .filter(|&n| all[n..] == before[..])
            .map(|n| all[..n].to_vec())
            .ok_or_else(|| FileError::Unsupported {
                feature:
                    "conclusion hedges that fuzzylite would not pass on to the next conclusion"
                        .to_string(),
                line: None,
            })?;
        c.hedges = crate::Hedges::new(&mine).unwrap_or_default();
        before = all;
    }
    Ok(own)
}

/// Refuses a rule that needs an operator its block leaves `none`.
fn check_operators<T>(e: &Expr, ops: &Block<T>, line: usize) -> Result<(), FileError> {
    match e {
        Expr::And(..) if ops.conjunction.is_none() => Err(missing(line, "conjunction", "`and`")),
        Expr::Or(..) if ops.disjunction.is_none() => Err(missing(line, "disjunction", "`or`")),
        Expr::And(a, b) | Expr::Or(a, b) => {
            check_operators(a, ops, line)?;
            check_operators(b, ops, line)
        }
        Expr::Is { .. } | Expr::Any { .. } | Expr::Output { .. } => Ok(()),
    }
}

fn missing(line: usize, operator: &'static str, needed_by: &str) -> FileError {
    FileError::MissingOperator {
        line,
        operator,
        needed_by: needed_by.to_string(),
    }
}

fn defuzzifier(value: &str, line: usize) -> Result<Defuzzifier, FileError> {
    let mut words = value.split_whitespace();
    let kind = words.next().unwrap_or("");
    if matches!(kind, "WeightedAverage" | "WeightedSum") {
        // fuzzylite's weighted defuzzifiers name a type, not a resolution.
        // They weigh Takagi–Sugeno / Tsukamoto terms (z = term(w)), not Mamdani centres: this
        // crate's centre averages are `CenterAverage` / its own `WeightedAverage`.
        let t = words.next().unwrap_or("Automatic");
        return Err(unsupported(
            line,
            format!("defuzzifier `{kind} {t}` (Takagi–Sugeno / Tsukamoto; this crate is Mamdani)"),
        ));
    }
    let res = match words.next() {
        None => Resolution::Midpoints(DEFAULT_RESOLUTION),
        Some(n) => Resolution::Midpoints(
            n.parse()
                .map_err(|_| syntax(line, format!("`{n}` is not a resolution")))?,
        ),
    };
    Ok(match kind {
        "Centroid" => Defuzzifier::Centroid(res),
        "Bisector" => Defuzzifier::Bisector(res),
        "MeanOfMaximum" => Defuzzifier::MeanOfMaximum(res),
        "SmallestOfMaximum" => Defuzzifier::SmallestOfMaximum(res),
        "LargestOfMaximum" => Defuzzifier::LargestOfMaximum(res),
        "CenterAverage" => Defuzzifier::CenterAverage,
        _ => return Err(syntax(line, format!("unknown defuzzifier `{kind}`"))),
    })
}

fn term<T: Real>(value: &str, line: usize) -> Result<Term<T>, FileError> {
    let mut words = value.split_whitespace();
    let (Some(name), Some(class)) = (words.next(), words.next()) else {
        return Err(syntax(line, "a term is `name Class parameters…`"));
    };
    let rest: String = words.collect::<Vec<_>>().join(" ");
    if matches!(class, "Constant" | "Linear" | "Function") {
        return Err(unsupported(
            line,
            format!("term class `{class}` (Takagi–Sugeno; this crate is Mamdani)"),
        ));
    }
    if matches!(class, "Arc" | "SemiEllipse") {
        return Err(unsupported(line, format!("term class `{class}`")));
    }
    let mut p: Vec<T> = numbers(&rest, line)?.into_iter().map(T::of).collect();
    // fuzzylite's optional last parameter is the term's height; 1 is the only one we take.
    let with_height = match class {
        "Discrete" => p.len() % 2 == 1,
        _ => p.len() == arity(class) + 1,
    };
    if with_height {
        if p.last() != Some(&T::one()) {
            return Err(unsupported(
                line,
                format!("term `{name}`: a height other than 1"),
            ));
        }
        p.pop();
    }
    let mf = match (class, &p[..]) {
        ("Discrete", &[_, _, ..]) => Mf::Discrete {
            points: p.chunks_exact(2).map(|xy| (xy[0], xy[1])).collect(),
        },
        ("Triangle", &[a, b, c]) => Mf::Triangle { a, b, c },
        ("Trapezoid", &[a, b, c, d]) => Mf::Trapezoid { a, b, c, d },
        ("Gaussian", &[mean, sigma]) => Mf::Gaussian { sigma, mean },
        ("GaussianProduct", &[mean1, sigma1, mean2, sigma2]) => Mf::Gaussian2 {
            sigma1,
            mean1,
            sigma2,
            mean2,
        },
        ("Bell", &[c, a, b]) => Mf::Bell { a, b, c },
        ("Sigmoid", &[c, a]) => Mf::Sigmoid { a, c },
        ("SigmoidDifference", &[c1, a1, a2, c2]) => Mf::SigmoidDifference { a1, c1, a2, c2 },
        ("SigmoidProduct", &[c1, a1, a2, c2]) => Mf::SigmoidProduct { a1, c1, a2, c2 },
        ("SShape", &[a, b]) => Mf::S { a, b },
        ("ZShape", &[a, b]) => Mf::Z { a, b },
        ("PiShape", &[a, b, c, d]) => Mf::Pi { a, b, c, d },
        ("Ramp", &[start, end]) => Mf::Ramp { start, end },
        // pyfuzzylite orders the edges itself.
        ("Rectangle", &[a, b]) => Mf::Rectangle {
            start: a.min(b),
            end: a.max(b),
        },
        ("Spike", &[center, width]) => Mf::Spike { center, width },
        ("Cosine", &[center, width]) => Mf::Cosine { center, width },
        ("Concave", &[inflection, end]) => Mf::Concave { inflection, end },
        ("Binary", &[start, direction]) if direction != start && !direction.is_nan() => {
            Mf::Binary {
                start,
                rising: direction > start,
            }
        }
        ("Binary", &[_, _]) => {
            return Err(syntax(
                line,
                format!("term `{name}`: a Binary direction on either side of its start"),
            ));
        }
        _ => {
            return Err(syntax(
                line,
                format!("`{class}` with {} parameters is not a known term", p.len()),
            ));
        }
    };
    mf.validate()
        .map_err(|e| syntax(line, format!("term `{name}`: {e}")))?;
    Ok(Term {
        name: name.to_string(),
        mf,
    })
}

/// An `activation:` value: fuzzylite's class name and its parameters (pyfuzzylite's defaults
/// when none are given; an absent or `none` method reads as `General`, as fuzzylite in C++).
fn activation_of<T: Real>(value: &str, line: usize) -> Result<Activation<T>, FileError> {
    let words: Vec<&str> = value.split_whitespace().collect();
    let count = |w: &str| {
        w.parse::<usize>()
            .map_err(|_| syntax(line, format!("`{w}` is not a rule count")))
    };
    let number = |w: &str| {
        w.parse::<f64>()
            .map(T::of)
            .map_err(|_| syntax(line, format!("`{w}` is not a number")))
    };
    Ok(match words[..] {
        [] | ["none"] | ["General"] => Activation::General,
        ["First" | "Last"] => first_last(words[0], 1, T::zero()),
        [kind @ ("First" | "Last"), n, t] => first_last(kind, count(n)?, number(t)?),
        ["Highest"] => Activation::Highest { rules: 1 },
        ["Highest", n] => Activation::Highest { rules: count(n)? },
        ["Lowest"] => Activation::Lowest { rules: 1 },
        ["Lowest", n] => Activation::Lowest { rules: count(n)? },
        ["Proportional"] => Activation::Proportional,
        ["Threshold"] => Activation::Threshold {
            comparison: Comparison::Greater,
            value: T::zero(),
        },
        ["Threshold", op, v] => Activation::Threshold {
            comparison: Comparison::ALL
                .iter()
                .find(|(_, s)| *s == op)
                .map(|(c, _)| *c)
                .ok_or_else(|| syntax(line, format!("`{op}` is not a comparison")))?,
            value: number(v)?,
        },
        [kind, ..] if Activation::<T>::NAMES.contains(&kind) => {
            return Err(syntax(
                line,
                format!("wrong parameters for activation `{kind}`"),
            ));
        }
        [kind, ..] => return Err(syntax(line, format!("unknown activation `{kind}`"))),
    })
}

fn first_last<T: Real>(kind: &str, rules: usize, threshold: T) -> Activation<T> {
    if kind == "First" {
        Activation::First { rules, threshold }
    } else {
        Activation::Last { rules, threshold }
    }
}

/// The `activation:` text of a method ([`activation_of`] reads it back).
fn activation_text<T: Real>(a: Activation<T>) -> String {
    match a {
        Activation::General | Activation::Proportional => a.name().to_string(),
        Activation::First { rules, threshold } | Activation::Last { rules, threshold } => {
            format!("{} {rules} {threshold}", a.name())
        }
        Activation::Highest { rules } | Activation::Lowest { rules } => {
            format!("{} {rules}", a.name())
        }
        Activation::Threshold { comparison, value } => {
            format!("Threshold {} {value}", comparison.symbol())
        }
    }
}

/// How many parameters a term class takes before its optional height (0: unknown class).
fn arity(class: &str) -> usize {
    match class {
        "SShape" | "ZShape" | "Gaussian" | "Sigmoid" | "Ramp" | "Rectangle" | "Spike"
        | "Cosine" | "Concave" | "Binary" => 2,
        "Triangle" | "Bell" => 3,
        "Trapezoid" | "GaussianProduct" | "SigmoidDifference" | "SigmoidProduct" | "PiShape" => 4,
        _ => usize::MAX - 1,
    }
}

/// Writes an engine as `.fll` text ([`from_fll`] reads it back to the same engine).
///
/// Exact resolutions are written as 100 000 midpoints; MATLAB's end-point samples as their
/// count with a comment that fuzzylite ignores and [`from_fll`] reads. Refused with
/// [`FileError::Unsupported`]: singleton terms, complemented conclusions (MATLAB's negative
/// index), an activation threshold.
pub fn to_fll<T: Real>(engine: &Engine<T>) -> Result<String, FileError> {
    let refuse = |feature: &str| {
        Err(FileError::Unsupported {
            feature: feature.to_string(),
            line: None,
        })
    };
    if engine
        .rules()
        .iter()
        .any(|r| r.consequents.iter().any(|c| c.negated))
    {
        return refuse("a complemented conclusion (MATLAB's negative output index)");
    }
    if engine.activation_threshold() > T::zero() {
        return refuse("an activation threshold");
    }
    let mut s = format!("Engine: {}\n", engine.name());
    for v in engine.inputs() {
        let lock = v.out_of_range == OutOfRange::Clamp;
        s += &format!(
            "InputVariable: {}\n  enabled: true\n  range: {} {}\n  lock-range: {lock}\n",
            v.name, v.min, v.max
        );
        write_terms(&mut s, &v.terms)?;
    }
    for v in engine.outputs() {
        s += &format!(
            "OutputVariable: {}\n  enabled: true\n  range: {} {}\n  lock-range: false\n",
            v.name, v.min, v.max
        );
        s += &format!("  aggregation: {}\n", name_of(&SNORMS, v.aggregation));
        let res = |r: Resolution| match r {
            Resolution::Samples(n) | Resolution::Midpoints(n) => n,
            Resolution::Exact => 100_000,
        };
        let marker = match v.defuzzifier.resolution() {
            Some(Resolution::Samples(_)) => format!(" {SAMPLES_MARKER}"),
            _ => String::new(),
        };
        let d = match v.defuzzifier {
            Defuzzifier::Centroid(r) => format!("Centroid {}", res(r)),
            Defuzzifier::Bisector(r) => format!("Bisector {}", res(r)),
            Defuzzifier::MeanOfMaximum(r) => format!("MeanOfMaximum {}", res(r)),
            Defuzzifier::SmallestOfMaximum(r) => format!("SmallestOfMaximum {}", res(r)),
            Defuzzifier::LargestOfMaximum(r) => format!("LargestOfMaximum {}", res(r)),
            Defuzzifier::WeightedAverage => {
                return refuse(
                    "this crate's WeightedAverage (fuzzylite's weighs Takagi–Sugeno terms)",
                );
            }
            Defuzzifier::CenterAverage => "CenterAverage".to_string(),
        };
        let default = v
            .default
            .map_or_else(|| "nan".to_string(), |d| d.to_string());
        s += &format!("  defuzzifier: {d}{marker}\n  default: {default}\n  lock-previous: false\n");
        write_terms(&mut s, &v.terms)?;
    }
    for block in engine.rule_blocks() {
        s += &format!(
            "RuleBlock: {}\n  enabled: true\n  conjunction: {}\n  disjunction: {}\n  implication: {}\n  activation: {}\n",
            block.name,
            name_of(&TNORMS, block.conjunction),
            name_of(&SNORMS, block.disjunction),
            name_of(&TNORMS, block.implication),
            activation_text(block.activation),
        );
        for r in &engine.rules()[block.rules.clone()] {
            let own = uncarry_hedges(r)?;
            s += &format!(
                "  rule: {}\n",
                rule_text(&own, engine.inputs(), engine.outputs())
            );
        }
    }
    Ok(s)
}

fn name_of<N: PartialEq + Copy>(table: &[(&'static str, N)], n: N) -> &'static str {
    table
        .iter()
        .find(|(_, v)| *v == n)
        .map_or("", |(name, _)| name)
}

fn write_terms<T: Real>(s: &mut String, terms: &[Term<T>]) -> Result<(), FileError> {
    for t in terms {
        let (class, p): (&str, Vec<T>) = match t.mf.clone() {
            Mf::Triangle { a, b, c } => ("Triangle", [a, b, c].into()),
            Mf::Trapezoid { a, b, c, d } => ("Trapezoid", [a, b, c, d].into()),
            Mf::Gaussian { sigma, mean } => ("Gaussian", [mean, sigma].into()),
            Mf::Gaussian2 {
                sigma1,
                mean1,
                sigma2,
                mean2,
            } => ("GaussianProduct", [mean1, sigma1, mean2, sigma2].into()),
            Mf::Bell { a, b, c } => ("Bell", [c, a, b].into()),
            Mf::Sigmoid { a, c } => ("Sigmoid", [c, a].into()),
            Mf::SigmoidDifference { a1, c1, a2, c2 } => {
                ("SigmoidDifference", [c1, a1, a2, c2].into())
            }
            Mf::SigmoidProduct { a1, c1, a2, c2 } => ("SigmoidProduct", [c1, a1, a2, c2].into()),
            Mf::S { a, b } => ("SShape", [a, b].into()),
            Mf::Z { a, b } => ("ZShape", [a, b].into()),
            Mf::Pi { a, b, c, d } => ("PiShape", [a, b, c, d].into()),
            Mf::Ramp { start, end } => ("Ramp", [start, end].into()),
            Mf::Rectangle { start, end } => ("Rectangle", [start, end].into()),
            Mf::Spike { center, width } => ("Spike", [center, width].into()),
            Mf::Cosine { center, width } => ("Cosine", [center, width].into()),
            Mf::Concave { inflection, end } => ("Concave", [inflection, end].into()),
            Mf::Binary { start, rising } => {
                let direction = if rising {
                    T::infinity()
                } else {
                    T::neg_infinity()
                };
                ("Binary", [start, direction].into())
            }
            Mf::Discrete { points } => {
                ("Discrete", points.iter().flat_map(|p| [p.0, p.1]).collect())
            }
            Mf::Singleton { .. } => {
                return Err(FileError::Unsupported {
                    feature: format!("singleton term `{}`", t.name),
                    line: None,
                });
            }
        };
        let params: Vec<String> = p.iter().map(|v| v.to_string()).collect();
        *s += &format!("  term: {} {} {}\n", t.name, class, params.join(" "));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Hedge, Hedges};

    const BASE: &str = "Engine: e
InputVariable: x
  range: 0 1
  term: lo Triangle 0 0 1
  term: hi Triangle 0 1 1
OutputVariable: a
  range: 0 1
  defuzzifier: Centroid 100
  term: t Triangle 0 1 1
OutputVariable: b
  range: 0 1
  defuzzifier: Centroid 100
  term: t Triangle 0 1 1
RuleBlock: r
  conjunction: none
  disjunction: Maximum
  implication: Minimum
  activation: General
  rule: if x is lo or x is any then a is not t and b is very t
";

    #[test]
    fn none_operators_hedges_and_carried_conclusion_hedges_import() -> Result<(), FileError> {
        let e = from_fll::<f64>(BASE)?;
        let c = &e.rules()[0].consequents;
        // fuzzylite passes `not` on to the next conclusion: b gets `very (not w)`.
        assert_eq!(c[0].hedges, Hedges::NOT);
        assert_eq!(
            c[1].hedges.iter().collect::<Vec<_>>(),
            [Hedge::Very, Hedge::Not]
        );
        // x is any: degree 1, so a gets `not 1` = 0 (no area: no value) and b `very 0`.
        let mut s = e.scratch();
        assert!(e.evaluate(&mut s, &[0.3]).is_err());
        let and = BASE.replace("x is lo or x is any", "x is lo and x is hi");
        assert_eq!(
            from_fll::<f64>(&and).unwrap_err(),
            FileError::MissingOperator {
                line: 19,
                operator: "conjunction",
                needed_by: "`and`".into()
            }
        );
        Ok(())
    }

    #[test]
    fn what_the_crate_lacks_is_a_typed_unsupported_with_its_line() {
        let cases = [
            ("term: hi Triangle 0 1 1", "term: hi SemiEllipse 0 1", 5),
            ("term: hi Triangle 0 1 1", "term: hi Arc 0 1", 5),
            ("term: hi Triangle 0 1 1", "term: hi Constant 0.5", 5),
            ("term: hi Triangle 0 1 1", "term: hi Triangle 0 1 1 0.5", 5),
            (
                "  range: 0 1\n  defuzzifier: Centroid 100\n  term: t Triangle 0 1 1\nOutputVariable: b",
                "  range: 0 1\n  lock-previous: true\n  term: t Triangle 0 1 1\nOutputVariable: b",
                8,
            ),
            ("InputVariable: x", "InputVariable: x\n  enabled: false", 3),
            (
                "defuzzifier: Centroid 100\n  term: t Triangle 0 1 1\nRuleBlock",
                "defuzzifier: WeightedSum\n  term: t Triangle 0 1 1\nRuleBlock",
                12,
            ),
        ];
        for (from, to, line) in cases {
            let text = BASE.replacen(from, to, 1);
            assert_ne!(text, BASE, "{from}");
            match from_fll::<f64>(&text) {
                Err(FileError::Unsupported { line: l, feature }) => {
                    assert_eq!(l, Some(line), "{to}: {feature}")
                }
                other => panic!("{to}: {other:?}"),
            }
        }
    }

    #[test]
    fn syntax_errors_name_line_and_column_and_unknown_names_are_typed() {
        let then = BASE.replace("then a is", "than a is");
        match from_fll::<f64>(&then) {
            Err(FileError::Syntax {
                line: 19,
                column,
                message,
            }) => {
                // `then` is missing: the column just past the rule's end.
                assert_eq!(column, 63, "{message}");
                assert!(message.contains("`then`"), "{message}");
            }
            other => panic!("{other:?}"),
        }
        let paren = BASE.replace("x is lo or x is any", "(x is lo or x is any");
        assert!(matches!(
            from_fll::<f64>(&paren),
            Err(FileError::Syntax { line: 19, .. })
        ));
        let term = BASE.replace("x is lo or", "x is mid or");
        assert_eq!(
            from_fll::<f64>(&term).unwrap_err(),
            FileError::Unknown {
                line: 19,
                what: "term",
                name: "mid".into()
            }
        );
        // No panic on any truncation of a valid file.
        for cut in 0..BASE.len() {
            let _ = from_fll::<f64>(&BASE[..cut]);
        }
    }

    /// A chained rule reads the conclusions before it; the edges of the syntax and of the
    /// formats are typed.
    #[test]
    fn chained_rules_read_earlier_conclusions_and_their_edges_are_typed() -> Result<(), FileError> {
        let chained = BASE.replace(
            "rule: if x is lo or x is any then a is not t and b is very t",
            "rule: if b is t then a is t\n  rule: if x is hi then b is t\n  rule: if b is very t then a is t with 0.5",
        );
        let e = from_fll::<f64>(&chained)?;
        assert!(e.rules()[0].antecedent.reads_outputs());
        assert_eq!(
            e.rules()[2].antecedent,
            crate::Expr::output(1, 0, Hedges::new(&[Hedge::Very]).expect("one hedge"))
        );
        let mut s = e.scratch();
        // x = 0.8: rule 1 reads b before anything concluded it (0), rule 2 concludes b at 0.8,
        // rule 3 reads very 0.8 = 0.64, weighted 0.5: a is t at 0.32, as `x is hi` (0.8)
        // weighted 0.4 gives it.
        let out = e.evaluate(&mut s, &[0.8]).expect("evaluates").to_vec();
        let only_rule_3 = from_fll::<f64>(&chained.replace(
            "rule: if b is very t then a is t with 0.5",
            "rule: if x is hi then a is t with 0.4",
        ))?;
        let mut s3 = only_rule_3.scratch();
        let want = only_rule_3.evaluate(&mut s3, &[0.8]).expect("evaluates");
        assert!((out[0] - want[0]).abs() < 1e-12, "{out:?} vs {want:?}");
        // Written and read back the same; MATLAB's format has no way to say it.
        assert_eq!(from_fll::<f64>(&to_fll(&e)?)?.rules(), e.rules());
        assert!(matches!(
            crate::to_fis(&e),
            Err(FileError::Unsupported { line: None, .. })
        ));
        // `output is any` has no meaning; a name that is no variable is unknown as such.
        let any = chained.replace("if b is t then", "if b is any then");
        assert!(matches!(
            from_fll::<f64>(&any),
            Err(FileError::Syntax { line: 19, .. })
        ));
        let nobody = chained.replace("if b is t then", "if c is t then");
        assert_eq!(
            from_fll::<f64>(&nobody).unwrap_err(),
            FileError::Unknown {
                line: 19,
                what: "variable",
                name: "c".into()
            }
        );
        // fuzzylite groups an output without aggregation by unbounded sum when a rule reads
        // it; refused, naming the rule's line.
        let none = chained.replacen(
            "OutputVariable: b\n  range: 0 1\n  defuzzifier: Centroid 100",
            "OutputVariable: b\n  range: 0 1\n  aggregation: none\n  defuzzifier: CenterAverage",
            1,
        );
        assert_ne!(none, chained);
        match from_fll::<f64>(&none) {
            Err(FileError::Unsupported { line, feature }) => {
                assert_eq!(line, Some(20), "{feature}");
                assert!(feature.contains("aggregation none"), "{feature}");
            }
            other => panic!("{other:?}"),
        }
        Ok(())
    }

    #[test]
    fn export_keeps_the_sampling_rule_and_hedges() -> Result<(), FileError> {
        let e = from_fll::<f64>(BASE)?;
        let back = from_fll::<f64>(&to_fll(&e)?)?;
        assert_eq!(back.rules(), e.rules());
        assert_eq!(back.outputs(), e.outputs());
        let matlab = e
            .with_resolution(Resolution::Samples(101))
            .map_err(FileError::Build)?;
        let text = to_fll(&matlab)?;
        assert!(text.contains(SAMPLES_MARKER));
        let back = from_fll::<f64>(&text)?;
        assert_eq!(
            back.outputs()[0].defuzzifier,
            Defuzzifier::Centroid(Resolution::Samples(101))
        );
        Ok(())
    }
}
