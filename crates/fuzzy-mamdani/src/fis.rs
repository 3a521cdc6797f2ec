//! MATLAB Fuzzy Logic Toolbox `.fis` files (Mamdani), read and written.
//!
//! Mapping notes: inputs are clamped to their range and an output for which no rule fires takes
//! the middle of its range, as MATLAB's `evalfis` does; the integral defuzzifiers use MATLAB's
//! default 101 samples (switch to the exact path with [`Engine::with_resolution`]).

use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

use crate::format::{FileError, at_line_start, numbers, syntax};
use crate::{
    BuildError, Consequent, Defuzzifier, Engine, EngineBuilder, Expr, Hedges, InputVariable, Mf,
    OutOfRange, OutputVariable, Real, Resolution, Rule, SNorm, TNorm, Term,
};

const MF_NAMES: [&str; 12] = [
    "trimf",
    "trapmf",
    "gaussmf",
    "gauss2mf",
    "gbellmf",
    "sigmf",
    "dsigmf",
    "psigmf",
    "smf",
    "zmf",
    "pimf",
    "singleton",
];

fn mf_from<T: Real>(kind: &str, p: &[f64], line: usize) -> Result<Mf<T>, FileError> {
    let p: Vec<T> = p.iter().map(|v| T::of(*v)).collect();
    Ok(match (kind, &p[..]) {
        ("trimf", &[a, b, c]) => Mf::Triangle { a, b, c },
        ("trapmf", &[a, b, c, d]) => Mf::Trapezoid { a, b, c, d },
        ("gaussmf", &[sigma, mean]) => Mf::Gaussian { sigma, mean },
        ("gauss2mf", &[sigma1, mean1, sigma2, mean2]) => Mf::Gaussian2 {
            sigma1,
            mean1,
            sigma2,
            mean2,
        },
        ("gbellmf", &[a, b, c]) => Mf::Bell { a, b, c },
        ("sigmf", &[a, c]) => Mf::Sigmoid { a, c },
        ("dsigmf", &[a1, c1, a2, c2]) => Mf::SigmoidDifference { a1, c1, a2, c2 },
        ("psigmf", &[a1, c1, a2, c2]) => Mf::SigmoidProduct { a1, c1, a2, c2 },
        ("smf", &[a, b]) => Mf::S { a, b },
        ("zmf", &[a, b]) => Mf::Z { a, b },
        ("pimf", &[a, b, c, d]) => Mf::Pi { a, b, c, d },
        ("singleton", &[x]) => Mf::Singleton { x },
        _ => {
            return Err(syntax(
                line,
                format!("`{kind}` with {} parameters is not a supported MF", p.len()),
            ));
        }
    })
}

/// MATLAB's name of a shape, `None` for fuzzylite's shapes MATLAB lacks.
fn mf_name<T>(mf: &Mf<T>) -> Option<&'static str> {
    let i = match mf {
        Mf::Triangle { .. } => 0,
        Mf::Trapezoid { .. } => 1,
        Mf::Gaussian { .. } => 2,
        Mf::Gaussian2 { .. } => 3,
        Mf::Bell { .. } => 4,
        Mf::Sigmoid { .. } => 5,
        Mf::SigmoidDifference { .. } => 6,
        Mf::SigmoidProduct { .. } => 7,
        Mf::S { .. } => 8,
        Mf::Z { .. } => 9,
        Mf::Pi { .. } => 10,
        Mf::Singleton { .. } => 11,
        Mf::Ramp { .. }
        | Mf::Rectangle { .. }
        | Mf::Spike { .. }
        | Mf::Cosine { .. }
        | Mf::Concave { .. }
        | Mf::Binary { .. }
        | Mf::Discrete { .. } => return None,
    };
    Some(MF_NAMES[i])
}

const DEFUZZ: [&str; 6] = ["centroid", "bisector", "mom", "som", "lom", "wtaver"];

fn defuzz_from(name: &str, line: usize) -> Result<Defuzzifier, FileError> {
    let r = Resolution::Samples(101);
    Ok(match name {
        "centroid" => Defuzzifier::Centroid(r),
        "bisector" => Defuzzifier::Bisector(r),
        "mom" => Defuzzifier::MeanOfMaximum(r),
        "som" => Defuzzifier::SmallestOfMaximum(r),
        "lom" => Defuzzifier::LargestOfMaximum(r),
        "wtaver" => Defuzzifier::CenterAverage,
        _ => return Err(syntax(line, format!("unsupported DefuzzMethod `{name}`"))),
    })
}

/// An output section as read: name, min, max, terms.
type OutputSection<T> = (String, T, T, Vec<Term<T>>);

enum Block {
    System,
    Input(usize),
    Output(usize),
    Rules,
}

/// Reads a Mamdani engine from `.fis` text.
///
/// ```
/// let fis = "[System]\nName='t'\nType='mamdani'\nAndMethod='min'\n\n[Input1]\nName='x'\nRange=[0 1]\n\
///            MF1='lo':'trimf',[0 0 1]\n\n[Output1]\nName='y'\nRange=[0 1]\nMF1='t':'trimf',[0 1 1]\n\n\
///            [Rules]\n1, 1 (1) : 1\n";
/// let engine = fuzzy_mamdani::from_fis::<f64>(fis)?;
/// assert_eq!(engine.outputs()[0].name, "y");
/// let bad = fis.replace("trimf',[0 0 1]", "trimf',[0 0]");
/// assert!(fuzzy_mamdani::from_fis::<f64>(&bad).unwrap_err().to_string().starts_with("line 9, column 1:"));
/// # Ok::<(), fuzzy_mamdani::FileError>(())
/// ```
pub fn from_fis<T: Real>(text: &str) -> Result<Engine<T>, FileError> {
    read_fis(text).map_err(|e| at_line_start(e, text))
}

fn read_fis<T: Real>(text: &str) -> Result<Engine<T>, FileError> {
    let mut name = String::new();
    let (mut and, mut or, mut imp, mut agg) = (
        TNorm::Minimum,
        SNorm::Maximum,
        TNorm::Minimum,
        SNorm::Maximum,
    );
    let mut defuzz = Defuzzifier::Centroid(Resolution::Samples(101));
    let (mut inputs, mut outputs): (Vec<InputVariable<T>>, Vec<OutputSection<T>>) =
        (Vec::new(), Vec::new());
    let mut rules = Vec::new();
    // Each rule's line, and the counts the file declares (value, line): checked at the end.
    let mut rule_lines = Vec::new();
    let mut declared: Vec<(&'static str, usize, usize)> = Vec::new();
    let mut mfs_declared: Vec<(usize, usize, (bool, usize))> = Vec::new();
    let mut block = Block::System;
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let content = raw.split('%').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        if let Some(section) = content.strip_prefix('[').and_then(|s| s.strip_suffix(']')) {
            block = section_of(section, line)?;
            match block {
                Block::Input(k) if k == inputs.len() => inputs.push(InputVariable {
                    name: String::new(),
                    min: T::zero(),
                    max: T::one(),
                    terms: Vec::new(),
                    out_of_range: OutOfRange::Clamp,
                }),
                Block::Output(k) if k == outputs.len() => {
                    outputs.push((String::new(), T::zero(), T::one(), Vec::new()))
                }
                Block::Input(_) | Block::Output(_) => {
                    return Err(syntax(line, "sections must be numbered 1, 2, … in order"));
                }
                _ => {}
            }
            continue;
        }
        if let Block::Rules = block {
            rules.push(fis_rule(content, line, &inputs, outputs.len())?);
            rule_lines.push(line);
            continue;
        }
        let (key, value) = content
            .split_once('=')
            .ok_or_else(|| syntax(line, "expected `Key=value`"))?;
        let (key, value) = (key.trim(), value.trim());
        let unquoted = value.trim_matches('\'');
        let (vname, vmin, vmax, vterms) = match block {
            Block::Input(k) => {
                let v = &mut inputs[k];
                (&mut v.name, &mut v.min, &mut v.max, &mut v.terms)
            }
            Block::Output(k) => {
                let v = &mut outputs[k];
                (&mut v.0, &mut v.1, &mut v.2, &mut v.3)
            }
            _ => {
                match key {
                    "Name" => name = unquoted.to_string(),
                    "Type" if unquoted == "mamdani" => {}
                    "Type" => {
                        return Err(syntax(
                            line,
                            format!("only Mamdani systems are supported, not `{unquoted}`"),
                        ));
                    }
                    "AndMethod" => {
                        and = pick(
                            unquoted,
                            &[("min", TNorm::Minimum), ("prod", TNorm::AlgebraicProduct)],
                            line,
                        )?
                    }
                    "OrMethod" => {
                        or = pick(
                            unquoted,
                            &[("max", SNorm::Maximum), ("probor", SNorm::AlgebraicSum)],
                            line,
                        )?
                    }
                    "ImpMethod" => {
                        imp = pick(
                            unquoted,
                            &[("min", TNorm::Minimum), ("prod", TNorm::AlgebraicProduct)],
                            line,
                        )?
                    }
                    "AggMethod" => {
                        let table = [
                            ("max", SNorm::Maximum),
                            ("sum", SNorm::UnboundedSum),
                            ("probor", SNorm::AlgebraicSum),
                        ];
                        agg = pick(unquoted, &table, line)?;
                    }
                    "DefuzzMethod" => defuzz = defuzz_from(unquoted, line)?,
                    "NumInputs" | "NumOutputs" | "NumRules" => {
                        let what = match key {
                            "NumInputs" => "NumInputs",
                            "NumOutputs" => "NumOutputs",
                            _ => "NumRules",
                        };
                        declared.push((what, count(unquoted, key, line)?, line));
                    }
                    _ => {} // Version, …
                }
                continue;
            }
        };
        match key {
            "Name" => *vname = unquoted.to_string(),
            "Range" => {
                let inner = value
                    .strip_prefix('[')
                    .and_then(|v| v.strip_suffix(']'))
                    .ok_or_else(|| syntax(line, "a range is `[min max]`, in brackets"))?;
                match numbers(inner, line)?[..] {
                    [a, b] => (*vmin, *vmax) = (T::of(a), T::of(b)),
                    _ => return Err(syntax(line, "a range is `[min max]`")),
                }
            }
            "NumMFs" => {
                // Checked once the section's MFs are all read (they follow it).
                mfs_declared.push((count(unquoted, key, line)?, line, block_index(&block)));
            }
            k if k.starts_with("MF") => vterms.push(fis_mf(value, line)?),
            _ => return Err(syntax(line, format!("unexpected key `{key}`"))),
        }
    }
    check_counts(&declared, &mfs_declared, &inputs, &outputs, rules.len())?;
    let mut b = EngineBuilder::new(name)
        .conjunction(and)
        .disjunction(or)
        .implication(imp);
    for v in inputs {
        b = b.input_variable(v);
    }
    for (name, min, max, terms) in outputs {
        let default = Some((min + max) / (T::one() + T::one()));
        b = b.output_variable(OutputVariable {
            name,
            min,
            max,
            terms,
            aggregation: agg,
            defuzzifier: defuzz,
            default,
        });
    }
    for r in rules {
        b = b.rule_struct(r);
    }
    b.build().map_err(|e| at_rule_line(e, &rule_lines))
}

/// A build error about rule `i` at the rule's own line, counted from 1; others as they are.
fn at_rule_line(e: BuildError, rule_lines: &[usize]) -> FileError {
    let line_of = |rule: usize| rule_lines.get(rule).copied().unwrap_or(0);
    match e {
        // A term index: the engine counts from 0, the file from 1.
        BuildError::Unknown {
            rule,
            what: "term",
            name,
        } => match name.parse::<usize>() {
            Ok(k) => syntax(
                line_of(rule),
                format!(
                    "rule {}: term {} does not exist (terms are the variable's MF1, MF2, …)",
                    rule + 1,
                    k + 1
                ),
            ),
            Err(_) => FileError::Unknown {
                line: line_of(rule),
                what: "term",
                name,
            },
        },
        BuildError::Unknown { rule, what, name } => FileError::Unknown {
            line: line_of(rule),
            what,
            name,
        },
        BuildError::BadRule { rule, reason } => {
            syntax(line_of(rule), format!("rule {}: {reason}", rule + 1))
        }
        e => FileError::Build(e),
    }
}

/// A `NumInputs=`-style count: a whole number.
fn count(value: &str, key: &str, line: usize) -> Result<usize, FileError> {
    value
        .parse()
        .map_err(|_| syntax(line, format!("{key} is a whole number, not `{value}`")))
}

/// Which variable a section is, for the `NumMFs` check: (is an output, index).
fn block_index(block: &Block) -> (bool, usize) {
    match block {
        Block::Output(k) => (true, *k),
        Block::Input(k) => (false, *k),
        _ => (false, usize::MAX),
    }
}

/// The counts the file declares against what it holds: `NumInputs`, `NumOutputs`,
/// `NumRules`, and each section's `NumMFs`.
fn check_counts<T: Real>(
    declared: &[(&'static str, usize, usize)],
    mfs: &[(usize, usize, (bool, usize))],
    inputs: &[InputVariable<T>],
    outputs: &[OutputSection<T>],
    rules: usize,
) -> Result<(), FileError> {
    for &(what, n, line) in declared {
        let (has, of) = match what {
            "NumInputs" => (inputs.len(), "[Input] sections"),
            "NumOutputs" => (outputs.len(), "[Output] sections"),
            _ => (rules, "rules under [Rules]"),
        };
        if n != has {
            return Err(syntax(
                line,
                format!("{what}={n}, but the file has {has} {of}"),
            ));
        }
    }
    for &(n, line, (output, k)) in mfs {
        let has = if output {
            outputs.get(k).map_or(0, |o| o.3.len())
        } else {
            inputs.get(k).map_or(0, |v| v.terms.len())
        };
        if n != has {
            return Err(syntax(
                line,
                format!("NumMFs={n}, but the section has {has} MFs"),
            ));
        }
    }
    Ok(())
}

fn section_of(s: &str, line: usize) -> Result<Block, FileError> {
    let index = |rest: &str| {
        rest.parse::<usize>()
            .ok()
            .filter(|k| *k >= 1)
            .map(|k| k - 1)
    };
    if s == "System" {
        Ok(Block::System)
    } else if s == "Rules" {
        Ok(Block::Rules)
    } else if let Some(k) = s.strip_prefix("Input").and_then(index) {
        Ok(Block::Input(k))
    } else if let Some(k) = s.strip_prefix("Output").and_then(index) {
        Ok(Block::Output(k))
    } else {
        Err(syntax(line, format!("unknown section `[{s}]`")))
    }
}

fn pick<N: Copy>(value: &str, table: &[(&str, N)], line: usize) -> Result<N, FileError> {
    table
        .iter()
        .find(|(n, _)| *n == value)
        .map(|(_, v)| *v)
        .ok_or_else(|| syntax(line, format!("unsupported method `{value}`")))
}

/// `'name':'type',[p1 p2 …]`
fn fis_mf<T: Real>(value: &str, line: usize) -> Result<Term<T>, FileError> {
    let bad = || syntax(line, "an MF is `'name':'type',[parameters]`");
    let (name, rest) = value.split_once(':').ok_or_else(bad)?;
    let (kind, params) = rest.split_once(',').ok_or_else(bad)?;
    let params = params
        .trim()
        .strip_prefix('[')
        .and_then(|p| p.strip_suffix(']'))
        .ok_or_else(bad)?;
    let mf = mf_from(
        kind.trim().trim_matches('\''),
        &numbers(params, line)?,
        line,
    )?;
    let name = name.trim().trim_matches('\'').to_string();
    mf.validate()
        .map_err(|e| syntax(line, format!("MF `{name}`: {e}")))?;
    Ok(Term { name, mf })
}

/// The largest term index a rule may name (far more terms than any variable has; it keeps the
/// cast to `usize` exact).
const MAX_TERM_INDEX: f64 = 65_536.0;

/// `i1 i2 …, o1 … (weight) : connection` with 1-based term indices, 0 absent, negative NOT.
fn fis_rule<T: Real>(
    text: &str,
    line: usize,
    inputs: &[InputVariable<T>],
    outputs: usize,
) -> Result<Rule<T>, FileError> {
    let bad = |m: &str| syntax(line, format!("rule: {m}"));
    let (body, conn) = text
        .rsplit_once(':')
        .ok_or_else(|| bad("missing `: connection`"))?;
    let (ante, rest) = body
        .split_once(',')
        .ok_or_else(|| bad("missing `,` between inputs and outputs"))?;
    let (outs, weight) = rest
        .split_once('(')
        .ok_or_else(|| bad("missing `(weight)`"))?;
    let weight = numbers(weight.trim().trim_end_matches(')'), line)?;
    let (ante, outs) = (numbers(ante, line)?, numbers(outs, line)?);
    if ante.len() != inputs.len() || outs.len() != outputs || weight.len() != 1 {
        return Err(bad(
            "needs one index per input, one per output and one weight",
        ));
    }
    let or = match numbers(conn, line)?[..] {
        [1.0] => false,
        [2.0] => true,
        _ => return Err(bad("connection is 1 (AND) or 2 (OR)")),
    };
    let mut antecedent: Option<Expr> = None;
    // A term index is a whole number ±1, ±2, …; 0.3 or NaN would have cast to 0 and
    // wrapped below it.
    let term_of = |k: f64| -> Result<usize, FileError> {
        if k.is_finite() && k.fract() == 0.0 && k.abs() >= 1.0 && k.abs() <= MAX_TERM_INDEX {
            Ok(k.abs() as usize - 1)
        } else {
            Err(bad(&format!(
                "term index {k} is not a whole number 1, 2, … (or its negative)"
            )))
        }
    };
    for (input, &k) in ante.iter().enumerate() {
        if k == 0.0 {
            continue;
        }
        let term = term_of(k)?;
        let hedges = if k < 0.0 { Hedges::NOT } else { Hedges::NONE };
        let e = Expr::hedged(input, term, hedges);
        antecedent = Some(match antecedent {
            None => e,
            Some(a) if or => a.or(e),
            Some(a) => a.and(e),
        });
    }
    let consequents = outs
        .iter()
        .enumerate()
        .filter(|(_, k)| **k != 0.0)
        .map(|(output, &k)| {
            Ok(Consequent {
                negated: k < 0.0,
                ..Consequent::new(output, term_of(k)?)
            })
        })
        .collect::<Result<_, FileError>>()?;
    let antecedent = antecedent.ok_or_else(|| bad("no input is used"))?;
    Ok(Rule {
        antecedent,
        consequents,
        weight: T::of(weight[0]),
    })
}

/// Writes a single-rule-block engine as MATLAB `.fis` text.
///
/// Fails with [`FileError::Unsupported`] for what MATLAB cannot express: nested AND / OR,
/// an input used twice in a rule, per-output operators that differ, norms other than MATLAB's.
pub fn to_fis<T: Real>(engine: &Engine<T>) -> Result<String, FileError> {
    let unsupported = |what: &str| FileError::Unsupported {
        feature: what.to_string(),
        line: None,
    };
    if engine
        .outputs()
        .iter()
        .any(|o| matches!(o.defuzzifier.resolution(), Some(Resolution::Midpoints(_))))
    {
        return Err(unsupported(
            "fuzzylite's midpoint integration (Resolution::Midpoints)",
        ));
    }
    if engine.activation_threshold() > T::zero() {
        return Err(unsupported("an activation threshold"));
    }
    if engine.rule_blocks().len() > 1 {
        return Err(unsupported("several rule blocks"));
    }
    if engine.activation() != crate::Activation::General {
        return Err(unsupported("an activation method other than General"));
    }
    let first = &engine.outputs()[0];
    if engine
        .outputs()
        .iter()
        .any(|o| o.aggregation != first.aggregation || o.defuzzifier != first.defuzzifier)
    {
        return Err(unsupported(
            "outputs with different aggregation or defuzzifier",
        ));
    }
    let t = |n: TNorm| match n {
        TNorm::Minimum => Ok("min"),
        TNorm::AlgebraicProduct => Ok("prod"),
        _ => Err(unsupported("a T-norm other than min / prod")),
    };
    let agg = match first.aggregation {
        SNorm::Maximum => "max",
        SNorm::UnboundedSum => "sum",
        SNorm::AlgebraicSum => "probor",
        _ => return Err(unsupported("an aggregation other than max / sum / probor")),
    };
    let or = match engine.disjunction() {
        SNorm::Maximum => "max",
        SNorm::AlgebraicSum => "probor",
        _ => return Err(unsupported("an OR other than max / probor")),
    };
    let defuzz = match first.defuzzifier {
        Defuzzifier::Centroid(_) => DEFUZZ[0],
        Defuzzifier::Bisector(_) => DEFUZZ[1],
        Defuzzifier::MeanOfMaximum(_) => DEFUZZ[2],
        Defuzzifier::SmallestOfMaximum(_) => DEFUZZ[3],
        Defuzzifier::LargestOfMaximum(_) => DEFUZZ[4],
        Defuzzifier::CenterAverage => DEFUZZ[5],
        Defuzzifier::WeightedAverage => {
            return Err(unsupported("the weighted-average defuzzifier"));
        }
    };
    let mut s = format!(
        "[System]\nName='{}'\nType='mamdani'\nVersion=2.0\nNumInputs={}\nNumOutputs={}\nNumRules={}\n\
         AndMethod='{}'\nOrMethod='{or}'\nImpMethod='{}'\nAggMethod='{agg}'\nDefuzzMethod='{defuzz}'\n",
        engine.name(),
        engine.inputs().len(),
        engine.outputs().len(),
        engine.rules().len(),
        t(engine.conjunction())?,
        t(engine.implication())?,
    );
    let vars = engine
        .inputs()
        .iter()
        .map(|v| ("Input", &v.name, v.min, v.max, &v.terms));
    let outs = engine
        .outputs()
        .iter()
        .map(|v| ("Output", &v.name, v.min, v.max, &v.terms));
    let (mut ni, mut no) = (0, 0);
    for (kind, name, min, max, terms) in vars.chain(outs) {
        let k = if kind == "Input" { &mut ni } else { &mut no };
        *k += 1;
        s += &format!(
            "\n[{kind}{k}]\nName='{name}'\nRange=[{min} {max}]\nNumMFs={}\n",
            terms.len()
        );
        for (j, term) in terms.iter().enumerate() {
            let (p, n) = term.mf.params();
            let p: Vec<String> = p[..n].iter().map(|v| v.to_string()).collect();
            let kind = mf_name(&term.mf).ok_or_else(|| {
                unsupported(&format!(
                    "term `{}`: a shape MATLAB has no MF for",
                    term.name
                ))
            })?;
            s += &format!("MF{}='{}':'{}',[{}]\n", j + 1, term.name, kind, p.join(" "));
        }
    }
    s += "\n[Rules]\n";
    for r in engine.rules() {
        if r.antecedent.reads_outputs() {
            return Err(unsupported(
                "an output variable in an antecedent (a chained engine)",
            ));
        }
        let mut ante = std::vec![0i64; engine.inputs().len()];
        let or = flatten(&r.antecedent, &mut ante, None)
            .ok_or_else(|| unsupported("a nested or repeated antecedent"))?;
        let mut outs = std::vec![0i64; engine.outputs().len()];
        for c in &r.consequents {
            if !c.hedges.is_empty() {
                return Err(unsupported("hedges on a rule's conclusion"));
            }
            outs[c.output] = if c.negated {
                -(c.term as i64 + 1)
            } else {
                c.term as i64 + 1
            };
        }
        let join = |v: &[i64]| {
            v.iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join(" ")
        };
        s += &format!(
            "{}, {} ({}) : {}\n",
            join(&ante),
            join(&outs),
            r.weight,
            if or == Some(true) { 2 } else { 1 }
        );
    }
    Ok(s)
}

/// Fills MATLAB's index row for a flat AND-chain or OR-chain; `Some(is_or)` (None: single term).
fn flatten(e: &Expr, row: &mut [i64], conn: Option<bool>) -> Option<Option<bool>> {
    match e {
        Expr::Is {
            input,
            term,
            hedges,
        } => {
            let slot = row.get_mut(*input)?;
            if *slot != 0 || !matches!(*hedges, Hedges::NONE | Hedges::NOT) {
                return None;
            }
            *slot = if *hedges == Hedges::NOT {
                -(*term as i64 + 1)
            } else {
                *term as i64 + 1
            };
            Some(conn)
        }
        Expr::And(a, b) | Expr::Or(a, b) => {
            let is_or = matches!(e, Expr::Or(..));
            if conn.is_some_and(|c| c != is_or) {
                return None;
            }
            flatten(a, row, Some(is_or))?;
            flatten(b, row, Some(is_or))
        }
        Expr::Any { .. } | Expr::Output { .. } => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Found by `cargo xtask fuzz fis` (fuzz/regressions/fis/term-index-0.3): a fractional or
    /// NaN term index cast to 0 and wrapped below it (a panic in debug builds).
    #[test]
    fn a_term_index_that_is_not_a_whole_number_is_a_syntax_error() {
        let head = "[System]\nName='t'\nType='mamdani'\nNumInputs=1\nNumOutputs=1\n\
                    NumRules=1\nAndMethod='min'\nOrMethod='max'\nImpMethod='min'\n\
                    AggMethod='max'\nDefuzzMethod='centroid'\n\n\
                    [Input1]\nName='x'\nRange=[0 1]\nNumMFs=1\nMF1='a':'trimf',[0 0.5 1]\n\n\
                    [Output1]\nName='y'\nRange=[0 1]\nNumMFs=1\nMF1='b':'trimf',[0 0.5 1]\n\n";
        assert!(from_fis::<f64>(&format!("{head}[Rules]\n1, 1 (1) : 1\n")).is_ok());
        for bad in ["0.3", "NaN", "-0.5", "1e300"] {
            let text = format!("{head}[Rules]\n1, {bad} (1) : 1\n");
            match from_fis::<f64>(&text) {
                Err(FileError::Syntax { message, .. }) => {
                    assert!(message.contains("term index"), "{bad}: {message}");
                }
                other => panic!("{bad}: {other:?}"),
            }
        }
    }

    const HEAD: &str = "[System]\nName='t'\nType='mamdani'\nNumInputs=1\nNumOutputs=1\n\
                        NumRules=1\nAndMethod='min'\nOrMethod='max'\nImpMethod='min'\n\
                        AggMethod='max'\nDefuzzMethod='centroid'\n\n\
                        [Input1]\nName='x'\nRange=[0 1]\nNumMFs=1\nMF1='a':'trimf',[0 0.5 1]\n\n\
                        [Output1]\nName='y'\nRange=[0 1]\nNumMFs=1\nMF1='b':'trimf',[0 0.5 1]\n\n\
                        [Rules]\n1, 1 (1) : 1\n";

    fn said(text: &str) -> String {
        match from_fis::<f64>(text) {
            Ok(_) => panic!("accepted:\n{text}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn a_rule_naming_a_term_the_variable_lacks_is_said_at_its_line_counted_from_one() {
        assert!(from_fis::<f64>(HEAD).is_ok());
        // Rule 1 (line 26) names output term 6 of a one-term output.
        let e = said(&HEAD.replace("1, 1 (1) : 1", "1, 6 (1) : 1"));
        assert_eq!(
            e,
            "line 26, column 1: rule 1: term 6 does not exist (terms are the variable's MF1, MF2, …)"
        );
    }

    #[test]
    fn a_malformed_range_and_counts_that_disagree_are_refused() {
        let e = said(&HEAD.replacen("Range=[0 1]", "Range=[0 30", 1));
        assert!(
            e.starts_with("line 15, column 1: a range is `[min max]`"),
            "{e}"
        );
        let e = said(&HEAD.replace("NumRules=1", "NumRules=3"));
        assert_eq!(
            e,
            "line 6, column 1: NumRules=3, but the file has 1 rules under [Rules]"
        );
        let e = said(&HEAD.replace("NumInputs=1", "NumInputs=2"));
        assert!(
            e.contains("NumInputs=2, but the file has 1 [Input] sections"),
            "{e}"
        );
        let e = said(&HEAD.replacen("NumMFs=1", "NumMFs=2", 1));
        assert!(e.contains("NumMFs=2, but the section has 1 MFs"), "{e}");
    }
}
