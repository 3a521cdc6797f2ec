//! fuzzylite's `.fll` format (fuzzylite 6 – 8), read and written.
//!
//! Mapping notes: `lock-range: true` clamps inputs, `false` evaluates them where they are
//! (fuzzylite's semantics); a `Centroid N` (etc.) reads as `N` samples with MATLAB's sampling
//! rule (fuzzylite integrates with `N` midpoints, so the two differ at low `N`); `default: nan`
//! means no default. `CenterAverage` is an extension of this crate (fuzzylite has none).

use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

use crate::format::{FileError, numbers, syntax};
use crate::{
    Defuzzifier, Engine, EngineBuilder, InputVariable, Mf, OutOfRange, OutputVariable, Real,
    Resolution, Rule, SNorm, TNorm, Term, parse_rule, rule_text,
};

const TNORMS: [(&str, TNorm); 6] = [
    ("Minimum", TNorm::Minimum),
    ("AlgebraicProduct", TNorm::AlgebraicProduct),
    ("BoundedDifference", TNorm::BoundedDifference),
    ("DrasticProduct", TNorm::DrasticProduct),
    ("EinsteinProduct", TNorm::EinsteinProduct),
    ("HamacherProduct", TNorm::HamacherProduct),
];
const SNORMS: [(&str, SNorm); 7] = [
    ("Maximum", SNorm::Maximum),
    ("AlgebraicSum", SNorm::AlgebraicSum),
    ("BoundedSum", SNorm::BoundedSum),
    ("DrasticSum", SNorm::DrasticSum),
    ("EinsteinSum", SNorm::EinsteinSum),
    ("HamacherSum", SNorm::HamacherSum),
    ("UnboundedSum", SNorm::UnboundedSum),
];

/// fuzzylite's resolution when a file gives none (pyfuzzylite 8's default).
const DEFAULT_RESOLUTION: usize = 1000;

enum Section {
    None,
    Input,
    Output,
    Rules,
}

/// Reads an engine from `.fll` text.
///
/// ```
/// let fll = "Engine: e\nInputVariable: x\n  range: 0 1\n  term: lo Triangle 0 0 1\n\
///            OutputVariable: y\n  range: 0 1\n  defuzzifier: Centroid 101\n  term: t Triangle 0 1 1\n\
///            RuleBlock: r\n  rule: if x is lo then y is t\n";
/// let engine = fuzzy_mamdani::from_fll::<f64>(fll)?;
/// assert_eq!(engine.rules().len(), 1);
/// let err = fuzzy_mamdani::from_fll::<f64>("Engine: e\nInputVariable: x\n  range: 0 one\n").unwrap_err();
/// assert_eq!(err.to_string(), "line 3: `one` is not a number");
/// # Ok::<(), fuzzy_mamdani::FileError>(())
/// ```
pub fn from_fll<T: Real>(text: &str) -> Result<Engine<T>, FileError> {
    let mut name = String::new();
    let (mut inputs, mut outputs, mut rules) = (
        Vec::new(),
        Vec::<OutputVariable<T>>::new(),
        Vec::<Rule<T>>::new(),
    );
    let (mut conj, mut disj, mut imp) = (TNorm::Minimum, SNorm::Maximum, TNorm::Minimum);
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
                    defuzzifier: Defuzzifier::Centroid(Resolution::Samples(DEFAULT_RESOLUTION)),
                    default: None,
                });
            }
            ("RuleBlock", _) => section = Section::Rules,
            ("enabled", _) if value == "true" => {}
            ("enabled", _) => {
                return Err(syntax(
                    line,
                    "disabled variables and rule blocks are not supported",
                ));
            }
            ("range", Section::Input) => {
                (last(&mut inputs, line)?.min, last(&mut inputs, line)?.max) = range(value, line)?
            }
            ("range", Section::Output) => {
                (last(&mut outputs, line)?.min, last(&mut outputs, line)?.max) = range(value, line)?
            }
            ("lock-range", Section::Input) => {
                last(&mut inputs, line)?.out_of_range = if value == "true" {
                    OutOfRange::Clamp
                } else {
                    OutOfRange::Evaluate
                };
            }
            ("lock-range" | "lock-previous" | "lock-valid", Section::Output) => {}
            ("term", Section::Input) => last(&mut inputs, line)?.terms.push(term(value, line)?),
            ("term", Section::Output) => last(&mut outputs, line)?.terms.push(term(value, line)?),
            ("aggregation", Section::Output) => {
                last(&mut outputs, line)?.aggregation = lookup(&SNORMS, value, line)?
            }
            ("defuzzifier", Section::Output) => {
                last(&mut outputs, line)?.defuzzifier = defuzzifier(value, line)?
            }
            ("default", Section::Output) => {
                let v: f64 = value
                    .parse()
                    .map_err(|_| syntax(line, format!("`{value}` is not a number")))?;
                last(&mut outputs, line)?.default = v.is_finite().then(|| T::of(v));
            }
            ("conjunction", Section::Rules) => conj = lookup(&TNORMS, value, line)?,
            ("disjunction", Section::Rules) => disj = lookup(&SNORMS, value, line)?,
            ("implication", Section::Rules) => imp = lookup(&TNORMS, value, line)?,
            ("activation", Section::Rules) if value.is_empty() || value == "General" => {}
            ("activation", Section::Rules) => {
                return Err(syntax(line, "only `General` activation is supported"));
            }
            ("rule", Section::Rules) => {
                let rule = parse_rule(value, rules.len(), &inputs, &outputs)
                    .map_err(|e| syntax(line, e.to_string()))?;
                rules.push(rule);
            }
            (k, _) => return Err(syntax(line, format!("unexpected `{k}` here"))),
        }
    }
    let mut b = EngineBuilder::new(name)
        .conjunction(conj)
        .disjunction(disj)
        .implication(imp);
    for v in inputs {
        b = b.input_variable(v);
    }
    for v in outputs {
        b = b.output_variable(v);
    }
    for r in rules {
        b = b.rule_struct(r);
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

fn lookup<N: Copy>(table: &[(&str, N)], value: &str, line: usize) -> Result<N, FileError> {
    table
        .iter()
        .find(|(n, _)| *n == value)
        .map(|(_, v)| *v)
        .ok_or_else(|| syntax(line, format!("unknown norm `{value}`")))
}

fn defuzzifier(value: &str, line: usize) -> Result<Defuzzifier, FileError> {
    let mut words = value.split_whitespace();
    let kind = words.next().unwrap_or("");
    let res = match words.next() {
        None => Resolution::Samples(DEFAULT_RESOLUTION),
        Some(n) => Resolution::Samples(
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
        "WeightedAverage" => Defuzzifier::WeightedAverage,
        "CenterAverage" => Defuzzifier::CenterAverage,
        _ => return Err(syntax(line, format!("unsupported defuzzifier `{kind}`"))),
    })
}

fn term<T: Real>(value: &str, line: usize) -> Result<Term<T>, FileError> {
    let mut words = value.split_whitespace();
    let (Some(name), Some(class)) = (words.next(), words.next()) else {
        return Err(syntax(line, "a term is `name Class parameters…`"));
    };
    let rest: String = words.collect::<Vec<_>>().join(" ");
    let p: Vec<T> = numbers(&rest, line)?.into_iter().map(T::of).collect();
    let mf = match (class, &p[..]) {
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
        ("Spike" | "Rectangle" | "Ramp" | "Cosine" | "Concave" | "Binary" | "Discrete", _) => {
            return Err(syntax(
                line,
                format!("term class `{class}` is not supported"),
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

/// Writes an engine as `.fll` text ([`from_fll`] reads it back to the same engine).
///
/// Exact resolutions are written as 100 000 samples, singleton terms are refused.
pub fn to_fll<T: Real>(engine: &Engine<T>) -> Result<String, FileError> {
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
            Resolution::Samples(n) => n,
            Resolution::Exact => 100_000,
        };
        let d = match v.defuzzifier {
            Defuzzifier::Centroid(r) => format!("Centroid {}", res(r)),
            Defuzzifier::Bisector(r) => format!("Bisector {}", res(r)),
            Defuzzifier::MeanOfMaximum(r) => format!("MeanOfMaximum {}", res(r)),
            Defuzzifier::SmallestOfMaximum(r) => format!("SmallestOfMaximum {}", res(r)),
            Defuzzifier::LargestOfMaximum(r) => format!("LargestOfMaximum {}", res(r)),
            Defuzzifier::WeightedAverage => "WeightedAverage".to_string(),
            Defuzzifier::CenterAverage => "CenterAverage".to_string(),
        };
        let default = v
            .default
            .map_or_else(|| "nan".to_string(), |d| d.to_string());
        s += &format!("  defuzzifier: {d}\n  default: {default}\n  lock-previous: false\n");
        write_terms(&mut s, &v.terms)?;
    }
    s += &format!(
        "RuleBlock: rules\n  enabled: true\n  conjunction: {}\n  disjunction: {}\n  implication: {}\n  activation: General\n",
        name_of(&TNORMS, engine.conjunction()),
        name_of(&SNORMS, engine.disjunction()),
        name_of(&TNORMS, engine.implication()),
    );
    for r in engine.rules() {
        s += &format!(
            "  rule: {}\n",
            rule_text(r, engine.inputs(), engine.outputs())
        );
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
        let (class, p): (&str, Vec<T>) = match t.mf {
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
            Mf::Singleton { .. } => {
                return Err(FileError::Unsupported(format!(
                    "singleton term `{}`",
                    t.name
                )));
            }
        };
        let params: Vec<String> = p.iter().map(|v| v.to_string()).collect();
        *s += &format!("  term: {} {} {}\n", t.name, class, params.join(" "));
    }
    Ok(())
}
