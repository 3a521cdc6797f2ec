//! Building an engine in Rust: variables, terms, operators, rules; checked once at `build`.

use alloc::string::{String, ToString};
use alloc::vec;
use alloc::vec::Vec;

use crate::defuzz::{self, Grid, Statistic};
use crate::engine::{AndIndex, Compiled, OutputPlan, ScratchShape};
use crate::rules::{self, MAX_DEPTH, Op};
use crate::{
    Activation, BuildError, Defuzzifier, Engine, Hedges, InputVariable, Mf, OutOfRange,
    OutputVariable, Real, Resolution, Rule, RuleBlock, SNorm, TNorm, Term,
};

/// The most samples a sampled defuzzifier may ask for (the table is terms × samples values).
pub const MAX_SAMPLES: usize = 1 << 20;

/// Builds an [`Engine`]. Operators default to MATLAB's Mamdani defaults: `min` AND, `max` OR,
/// `min` implication, `max` aggregation, centroid over 101 samples, inputs clamped to their range,
/// no default output (no rule firing is an error).
///
/// Settings made on the builder (`aggregation`, `defuzzifier`, `default_value`,
/// `out_of_range`) apply to the variables added with [`input`](Self::input) /
/// [`output`](Self::output); variables added whole with [`input_variable`](Self::input_variable) /
/// [`output_variable`](Self::output_variable) keep their own.
#[derive(Debug, Clone)]
pub struct EngineBuilder<T> {
    name: String,
    inputs: Vec<(InputVariable<T>, bool)>,
    outputs: Vec<(OutputVariable<T>, bool)>,
    rules: Vec<RuleSource<T>>,
    conjunction: TNorm,
    disjunction: SNorm,
    implication: TNorm,
    aggregation: SNorm,
    defuzzifier: Defuzzifier,
    default: Option<T>,
    out_of_range: OutOfRange,
    activation_threshold: T,
    activation: Activation<T>,
    /// The current block's name; `blocks` holds the blocks closed before it.
    block: String,
    blocks: Vec<RuleBlock<T>>,
}

#[derive(Debug, Clone)]
enum RuleSource<T> {
    Text(String),
    Built(Rule<T>),
}

fn terms<T, S: Into<String>>(terms: impl IntoIterator<Item = (S, Mf<T>)>) -> Vec<Term<T>> {
    terms
        .into_iter()
        .map(|(name, mf)| Term {
            name: name.into(),
            mf,
        })
        .collect()
}

impl<T: Real> EngineBuilder<T> {
    /// An empty engine called `name`.
    pub fn new(name: impl Into<String>) -> Self {
        EngineBuilder {
            name: name.into(),
            inputs: Vec::new(),
            outputs: Vec::new(),
            rules: Vec::new(),
            conjunction: TNorm::Minimum,
            disjunction: SNorm::Maximum,
            implication: TNorm::Minimum,
            aggregation: SNorm::Maximum,
            defuzzifier: Defuzzifier::Centroid(Resolution::Samples(101)),
            default: None,
            out_of_range: OutOfRange::Clamp,
            activation_threshold: T::zero(),
            activation: Activation::General,
            block: String::from("rules"),
            blocks: Vec::new(),
        }
    }

    /// Adds an input over `[min, max]` with named terms.
    pub fn input<S: Into<String>>(
        mut self,
        name: impl Into<String>,
        min: T,
        max: T,
        terms_: impl IntoIterator<Item = (S, Mf<T>)>,
    ) -> Self {
        let var = InputVariable {
            name: name.into(),
            min,
            max,
            terms: terms(terms_),
            out_of_range: self.out_of_range,
        };
        self.inputs.push((var, false));
        self
    }

    /// Adds an output over `[min, max]` with named terms.
    pub fn output<S: Into<String>>(
        mut self,
        name: impl Into<String>,
        min: T,
        max: T,
        terms_: impl IntoIterator<Item = (S, Mf<T>)>,
    ) -> Self {
        let var = OutputVariable {
            name: name.into(),
            min,
            max,
            terms: terms(terms_),
            aggregation: self.aggregation,
            defuzzifier: self.defuzzifier,
            default: self.default,
        };
        self.outputs.push((var, false));
        self
    }

    /// Adds a fully specified input, which keeps its own out-of-range policy.
    pub fn input_variable(mut self, var: InputVariable<T>) -> Self {
        self.inputs.push((var, true));
        self
    }

    /// Adds a fully specified output, which keeps its own aggregation, defuzzifier and default.
    pub fn output_variable(mut self, var: OutputVariable<T>) -> Self {
        self.outputs.push((var, true));
        self
    }

    /// Adds a rule in fuzzylite's syntax (see [`crate::parse_rule`]), parsed at `build`.
    pub fn rule(mut self, text: impl Into<String>) -> Self {
        self.rules.push(RuleSource::Text(text.into()));
        self
    }

    /// Adds a rule given by indices.
    pub fn rule_struct(mut self, rule: Rule<T>) -> Self {
        self.rules.push(RuleSource::Built(rule));
        self
    }

    /// The T-norm for `and`.
    pub fn conjunction(mut self, t: TNorm) -> Self {
        self.conjunction = t;
        self
    }
    /// The S-norm for `or`.
    pub fn disjunction(mut self, s: SNorm) -> Self {
        self.disjunction = s;
        self
    }
    /// The implication T-norm (min clips, product scales).
    pub fn implication(mut self, t: TNorm) -> Self {
        self.implication = t;
        self
    }
    /// The aggregation S-norm of the outputs added with [`output`](Self::output).
    pub fn aggregation(mut self, s: SNorm) -> Self {
        self.aggregation = s;
        self
    }
    /// The defuzzifier of the outputs added with [`output`](Self::output).
    pub fn defuzzifier(mut self, d: Defuzzifier) -> Self {
        self.defuzzifier = d;
        self
    }
    /// The value the outputs added with [`output`](Self::output) take when no rule fires.
    pub fn default_value(mut self, v: T) -> Self {
        self.default = Some(v);
        self
    }
    /// A conclusion takes part only when its activation degree (its rule's weighted strength,
    /// hedged) is above `t`: 0 (the default, MATLAB's and pyfuzzylite 8's) drops silent rules
    /// only; fuzzylite 6 / 7 in C++ use `1e-6` (its `macheps` comparison), which also drops
    /// rules that fire faintly. In `[0, 1)`; checked at `build`.
    pub fn activation_threshold(mut self, t: T) -> Self {
        self.activation_threshold = t;
        self
    }
    /// How the rules' degrees decide which rules take part (default [`Activation::General`]:
    /// all of them).
    pub fn activation(mut self, a: Activation<T>) -> Self {
        self.activation = a;
        self
    }
    /// Closes the current rule block and starts another called `name`: the rules added from
    /// here on belong to it, and `conjunction`, `disjunction`, `implication` and `activation`
    /// set its operators (it starts with the closed block's). fuzzylite's several
    /// `RuleBlock`s; MATLAB has one.
    ///
    /// ```
    /// use fuzzy_mamdani::{Activation, EngineBuilder, Mf, TNorm};
    /// let tri = |a, b, c| Mf::Triangle { a, b, c };
    /// let e = EngineBuilder::<f64>::new("two blocks")
    ///     .input("x", 0.0, 1.0, [("lo", tri(0.0, 0.0, 1.0)), ("hi", tri(0.0, 1.0, 1.0))])
    ///     .output("y", 0.0, 1.0, [("a", tri(0.0, 0.0, 1.0)), ("b", tri(0.0, 1.0, 1.0))])
    ///     .rule("if x is lo then y is a")
    ///     .rule_block("strongest")
    ///     .implication(TNorm::AlgebraicProduct)
    ///     .activation(Activation::Highest { rules: 1 })
    ///     .rule("if x is hi then y is b")
    ///     .rule("if x is lo then y is b with 0.5")
    ///     .build()?;
    /// assert_eq!(e.rule_blocks().len(), 2);
    /// assert_eq!(e.rule_blocks()[1].rules, 1..3);
    /// # Ok::<(), fuzzy_mamdani::BuildError>(())
    /// ```
    pub fn rule_block(mut self, name: impl Into<String>) -> Self {
        let start = self.blocks.last().map_or(0, |b| b.rules.end);
        self.blocks.push(RuleBlock {
            name: core::mem::replace(&mut self.block, name.into()),
            conjunction: self.conjunction,
            disjunction: self.disjunction,
            implication: self.implication,
            activation: self.activation,
            rules: start..self.rules.len(),
        });
        self
    }
    /// The out-of-range policy of the inputs added with [`input`](Self::input).
    pub fn out_of_range(mut self, p: OutOfRange) -> Self {
        self.out_of_range = p;
        self
    }

    /// Checks everything and precomputes what evaluation needs.
    pub fn build(self) -> Result<Engine<T>, BuildError> {
        let b = &self;
        let inputs: Vec<InputVariable<T>> = b
            .inputs
            .iter()
            .map(|(v, own)| InputVariable {
                out_of_range: if *own { v.out_of_range } else { b.out_of_range },
                ..v.clone()
            })
            .collect();
        let outputs: Vec<OutputVariable<T>> = b
            .outputs
            .iter()
            .map(|(v, own)| match own {
                true => v.clone(),
                false => OutputVariable {
                    aggregation: b.aggregation,
                    defuzzifier: b.defuzzifier,
                    default: b.default,
                    ..v.clone()
                },
            })
            .collect();
        if inputs.is_empty() || outputs.is_empty() {
            return Err(BuildError::Empty);
        }
        if !(b.activation_threshold >= T::zero() && b.activation_threshold < T::one()) {
            return Err(BuildError::BadThreshold);
        }
        let mut blocks = b.blocks.clone();
        blocks.push(RuleBlock {
            name: b.block.clone(),
            conjunction: b.conjunction,
            disjunction: b.disjunction,
            implication: b.implication,
            activation: b.activation,
            rules: blocks.last().map_or(0, |l| l.rules.end)..b.rules.len(),
        });
        if blocks.iter().any(|k| !k.activation.is_valid()) {
            return Err(BuildError::BadThreshold);
        }
        let mut names: Vec<&str> = Vec::new();
        for (name, min, max, terms) in inputs
            .iter()
            .map(|v| (&v.name, v.min, v.max, &v.terms))
            .chain(outputs.iter().map(|v| (&v.name, v.min, v.max, &v.terms)))
        {
            check_variable(name, min, max, terms)?;
            if names.contains(&name.as_str()) {
                return Err(BuildError::DuplicateName { name: name.clone() });
            }
            names.push(name);
        }
        let mut rules_ = Vec::with_capacity(b.rules.len());
        for (i, src) in b.rules.iter().enumerate() {
            let rule = match src {
                RuleSource::Text(t) => rules::parse_rule(t, i, &inputs, &outputs)?,
                RuleSource::Built(r) => r.clone(),
            };
            check_rule(&rule, i, &inputs, &outputs)?;
            rules_.push(rule);
        }
        for (o, var) in outputs.iter().enumerate() {
            // An output whose every conclusion has weight 0 (and no hedge to lift it) can never
            // fire: without a default it could never answer.
            let live = rules_.iter().any(|r| {
                r.consequents
                    .iter()
                    .any(|c| c.output == o && (r.weight > T::zero() || !c.hedges.is_empty()))
            });
            if !live && var.default.is_none() {
                return Err(BuildError::NeverAnswers {
                    output: var.name.clone(),
                });
            }
            let negated = rules_
                .iter()
                .flat_map(|r| &r.consequents)
                .any(|c| c.output == o && c.negated);
            // Under the implication of every block that concludes on this output.
            for k in &blocks {
                if rules_[k.rules.clone()]
                    .iter()
                    .any(|r| r.consequents.iter().any(|c| c.output == o))
                {
                    check_defuzzifier(var, k.implication, negated)?;
                }
            }
            check_defuzzifier(var, blocks[0].implication, negated)?;
        }
        let compiled = compile(&inputs, &outputs, &rules_, &blocks);
        Ok(Engine {
            name: self.name,
            inputs,
            outputs,
            rules: rules_,
            blocks,
            activation_threshold: self.activation_threshold,
            compiled,
        })
    }
}

fn check_variable<T: Real>(
    name: &str,
    min: T,
    max: T,
    terms: &[Term<T>],
) -> Result<(), BuildError> {
    if !(min.is_finite() && max.is_finite() && min < max) {
        return Err(BuildError::BadRange {
            variable: name.to_string(),
        });
    }
    if terms.is_empty() {
        return Err(BuildError::NoTerms {
            variable: name.to_string(),
        });
    }
    for (i, t) in terms.iter().enumerate() {
        t.mf.validate().map_err(|source| BuildError::BadTerm {
            variable: name.to_string(),
            term: t.name.clone(),
            source,
        })?;
        if terms[..i].iter().any(|u| u.name == t.name) {
            return Err(BuildError::DuplicateName {
                name: t.name.clone(),
            });
        }
    }
    Ok(())
}

fn check_rule<T: Real>(
    rule: &Rule<T>,
    i: usize,
    inputs: &[InputVariable<T>],
    outputs: &[OutputVariable<T>],
) -> Result<(), BuildError> {
    fn check_expr<T>(
        e: &crate::Expr,
        i: usize,
        inputs: &[InputVariable<T>],
        outputs: &[OutputVariable<T>],
    ) -> Result<(), BuildError> {
        // A variable index and a term index within it, checked against `terms` (per variable).
        let known = |what: &'static str, var: usize, term: Option<usize>, terms: Option<usize>| {
            let (name, what) = match (terms, term) {
                (None, _) => (var, what),
                (Some(n), Some(t)) if t >= n => (t, "term"),
                _ => return Ok(()),
            };
            Err(BuildError::Unknown {
                rule: i,
                what,
                name: name.to_string(),
            })
        };
        let input_terms = |v: usize| inputs.get(v).map(|v| v.terms.len());
        match e {
            crate::Expr::Output { output, term, .. } => known(
                "output",
                *output,
                Some(*term),
                outputs.get(*output).map(|v| v.terms.len()),
            ),
            crate::Expr::Any { input, .. } => known("input", *input, None, input_terms(*input)),
            crate::Expr::Is { input, term, .. } => {
                known("input", *input, Some(*term), input_terms(*input))
            }
            crate::Expr::And(a, b) | crate::Expr::Or(a, b) => {
                check_expr(a, i, inputs, outputs)?;
                check_expr(b, i, inputs, outputs)
            }
        }
    }
    check_expr(&rule.antecedent, i, inputs, outputs)?;
    if rule.antecedent.depth() > MAX_DEPTH {
        return Err(BuildError::BadRule {
            rule: i,
            reason: "antecedent nests deeper than 16",
        });
    }
    if rule.consequents.is_empty() {
        return Err(BuildError::BadRule {
            rule: i,
            reason: "no consequent",
        });
    }
    if !(rule.weight >= T::zero() && rule.weight <= T::one()) {
        return Err(BuildError::BadRule {
            rule: i,
            reason: "weight must be in [0, 1]",
        });
    }
    for c in &rule.consequents {
        match outputs.get(c.output) {
            None => {
                return Err(BuildError::Unknown {
                    rule: i,
                    what: "output",
                    name: c.output.to_string(),
                });
            }
            Some(v) if c.term >= v.terms.len() => {
                return Err(BuildError::Unknown {
                    rule: i,
                    what: "term",
                    name: c.term.to_string(),
                });
            }
            Some(_) => {}
        }
    }
    Ok(())
}

fn check_defuzzifier<T: Real>(
    var: &OutputVariable<T>,
    implication: TNorm,
    negated: bool,
) -> Result<(), BuildError> {
    let fail = |reason| {
        Err(BuildError::Defuzzifier {
            output: var.name.clone(),
            reason,
        })
    };
    if var.default.is_some_and(|d| !d.is_finite()) {
        return fail("the default value must be finite");
    }
    let singleton = var
        .terms
        .iter()
        .any(|t| matches!(t.mf, Mf::Singleton { .. }));
    match var.defuzzifier.resolution() {
        None if negated => {
            fail("the averaging defuzzifiers need terms with a centre, not their complements")
        }
        None => Ok(()),
        Some(_) if singleton => fail("a singleton term has no area: use an averaging defuzzifier"),
        Some(Resolution::Samples(n)) if !(2..=MAX_SAMPLES).contains(&n) => {
            fail("samples must be in 2..=2^20")
        }
        Some(Resolution::Midpoints(n)) if !(1..=MAX_SAMPLES).contains(&n) => {
            fail("midpoints must be in 1..=2^20")
        }
        Some(Resolution::Samples(n) | Resolution::Midpoints(n)) => {
            // A term no sample sees can never shape the answer: whether a rule concluding it
            // gives a value would depend on where the samples fall.
            let grid = Grid::new(
                var.min,
                var.max,
                n,
                matches!(var.defuzzifier.resolution(), Some(Resolution::Midpoints(_))),
            );
            let seen =
                |mf: &Mf<T>| (0..n).any(|k| mf.membership(grid.x(T::of(k as f64))) > T::zero());
            if var.terms.iter().all(|t| seen(&t.mf)) {
                Ok(())
            } else {
                fail(
                    "a term lies between the samples (no sample sees it): widen it or raise the resolution",
                )
            }
        }
        Some(Resolution::Exact)
            if var.terms.iter().any(|t| match t.mf {
                Mf::Triangle { a, c, .. } => !(c > a),
                Mf::Trapezoid { a, d, .. } => !(d > a),
                _ => false,
            }) =>
        {
            fail("a term has no area (zero width): the exact path never sees it")
        }
        Some(Resolution::Exact)
            if var
                .terms
                .iter()
                .any(|t| t.mf.linear_breakpoints().is_none()) =>
        {
            fail("the exact path needs triangle / trapezoid terms")
        }
        Some(Resolution::Exact)
            if !matches!(implication, TNorm::Minimum | TNorm::AlgebraicProduct) =>
        {
            fail("the exact path needs min or product implication")
        }
        Some(Resolution::Exact)
            if !matches!(var.aggregation, SNorm::Maximum | SNorm::UnboundedSum) =>
        {
            fail("the exact path needs max or unbounded-sum aggregation")
        }
        Some(Resolution::Exact) => Ok(()),
    }
}

fn compile<T: Real>(
    inputs: &[InputVariable<T>],
    outputs: &[OutputVariable<T>],
    rules_: &[Rule<T>],
    blocks: &[RuleBlock<T>],
) -> Compiled<T> {
    let general = blocks.len() == 1 && blocks[0].activation == Activation::General;
    let mut implications = vec![TNorm::Minimum; rules_.len()];
    for k in blocks {
        implications[k.rules.clone()].fill(k.implication);
    }
    let mut input_offsets = Vec::with_capacity(inputs.len() + 1);
    let mut input_mfs = Vec::new();
    for v in inputs {
        input_offsets.push(input_mfs.len());
        input_mfs.extend(v.terms.iter().map(|t| t.mf.clone()));
    }
    input_offsets.push(input_mfs.len());
    // A chained engine keeps each output term's conclusions so far after the input terms.
    let chained = rules_.iter().any(|r| r.antecedent.reads_outputs());
    let mut output_offsets = Vec::with_capacity(outputs.len() + 1);
    let mut output_terms = 0;
    for v in outputs {
        output_offsets.push(input_mfs.len() + output_terms);
        output_terms += v.terms.len();
    }
    output_offsets.push(input_mfs.len() + output_terms);
    let (mut ops, mut rule_ops, mut weights) = (Vec::new(), Vec::new(), Vec::new());
    for r in rules_ {
        let start = ops.len() as u32;
        rules::compile(&r.antecedent, &input_offsets, &output_offsets, &mut ops);
        rule_ops.push((start, ops.len() as u32));
        weights.push(r.weight);
    }
    let and_pairs = rule_ops
        .iter()
        .map(|&(lo, hi)| match ops[lo as usize..hi as usize] {
            [
                Op::Term {
                    mu: a,
                    hedges: Hedges::NONE,
                },
                Op::Term {
                    mu: b,
                    hedges: Hedges::NONE,
                },
                Op::And,
            ] => Some([a, b]),
            _ => None,
        })
        .collect::<Option<Vec<_>>>()
        // A hedged conclusion can act on a rule that did not fire (`not` of 0 is 1), and the
        // other activation methods look at every rule.
        .filter(|_| {
            general
                && !chained
                && rules_
                    .iter()
                    .all(|r| r.consequents.iter().all(|c| c.hedges.is_empty()))
        });
    let and_index = and_pairs.map(|pairs| and_index(&pairs, input_mfs.len()));
    let plans: Vec<OutputPlan<T>> = outputs
        .iter()
        .enumerate()
        .map(|(o, v)| plan(o, v, rules_))
        .collect();
    let shape = ScratchShape {
        input_terms: input_mfs.len(),
        output_terms: if chained { output_terms } else { 0 },
        rules: rules_.len(),
        acts: plans
            .iter()
            .map(|p| p.consequents.len().max(2 * p.mfs.len()))
            .max()
            .unwrap_or(0),
        levels: 2 * outputs.iter().map(|v| v.terms.len()).max().unwrap_or(0),
        samples: plans.iter().map(|p| p.samples).max().unwrap_or(0),
        outputs: outputs.len(),
    };
    let single = blocks[1..]
        .iter()
        .all(|k| k.implication == blocks[0].implication);
    Compiled {
        input_offsets,
        input_mfs,
        output_offsets: chained.then_some(output_offsets),
        ops,
        rule_ops,
        and_index,
        weights,
        implications,
        implication: single.then_some(blocks[0].implication),
        plans,
        shape,
    }
}

/// CSR of `(b, rule)` by first membership `a`, rules in ascending order within each `a`.
fn and_index(pairs: &[[u32; 2]], terms: usize) -> AndIndex {
    let mut offsets = vec![0u32; terms + 1];
    for p in pairs {
        offsets[p[0] as usize + 1] += 1;
    }
    for a in 0..terms {
        offsets[a + 1] += offsets[a];
    }
    let mut next = offsets.clone();
    let mut entries = vec![(0, 0); pairs.len()];
    for (r, p) in pairs.iter().enumerate() {
        let slot = &mut next[p[0] as usize];
        entries[*slot as usize] = (p[1], r as u32);
        *slot += 1;
    }
    AndIndex { offsets, entries }
}

fn plan<T: Real>(o: usize, v: &OutputVariable<T>, rules_: &[Rule<T>]) -> OutputPlan<T> {
    let mfs: Vec<Mf<T>> = v.terms.iter().map(|t| t.mf.clone()).collect();
    let consequents = rules_
        .iter()
        .enumerate()
        .flat_map(|(r, rule)| rule.consequents.iter().map(move |c| (r, c)))
        .filter(|(_, c)| c.output == o)
        .map(|(r, c)| (r as u32, c.term as u32, c.negated, c.hedges))
        .collect::<Vec<_>>();
    // Consequents come in rule order, so each rule's are one contiguous run.
    let mut rule_offsets = vec![0u32; rules_.len() + 1];
    for &(r, _, _, _) in &consequents {
        rule_offsets[r as usize + 1] += 1;
    }
    for r in 0..rules_.len() {
        rule_offsets[r + 1] += rule_offsets[r];
    }
    let (samples, midpoints) = match v.defuzzifier.resolution() {
        Some(Resolution::Samples(n)) => (n, false),
        Some(Resolution::Midpoints(n)) => (n, true),
        _ => (0, false),
    };
    let grid = Grid::new(v.min, v.max, samples, midpoints);
    let mut table = Vec::with_capacity(samples * mfs.len());
    for mf in &mfs {
        table.extend((0..samples).map(|k| mf.membership(grid.x(T::of(k as f64)))));
    }
    let centers = mfs
        .iter()
        .map(|mf| {
            mf.center()
                .unwrap_or_else(|| term_centroid(mf, v.min, v.max))
        })
        .collect();
    OutputPlan {
        mfs,
        centers,
        hedged: consequents.iter().any(|c| !c.3.is_empty()),
        consequents,
        rule_offsets,
        stat: Statistic::of(v.defuzzifier),
        samples,
        grid,
        table,
    }
}

/// The centroid of a term without a natural centre, over 1001 samples of the universe.
fn term_centroid<T: Real>(mf: &Mf<T>, min: T, max: T) -> T {
    let n = 1001;
    let grid = Grid::new(min, max, n, false);
    let mu: Vec<T> = (0..n)
        .map(|k| mf.membership(grid.x(T::of(k as f64))))
        .collect();
    defuzz::sampled(Statistic::Centroid, &mu, &grid)
        .unwrap_or_else(|| crate::mf::midpoint(min, max))
}

impl<T: Real> From<&Engine<T>> for EngineBuilder<T> {
    /// A builder holding the engine's variables (with their own settings) and rules, to edit.
    fn from(engine: &Engine<T>) -> Self {
        let mut b = EngineBuilder::new(engine.name.clone())
            .activation_threshold(engine.activation_threshold);
        let (last, closed) = engine
            .blocks
            .split_last()
            .map_or((None, &[][..]), |(l, c)| (Some(l), c));
        b.blocks = closed.to_vec();
        if let Some(last) = last {
            b.block = last.name.clone();
            b = b
                .conjunction(last.conjunction)
                .disjunction(last.disjunction)
                .implication(last.implication)
                .activation(last.activation);
        }
        b.inputs = engine.inputs.iter().map(|v| (v.clone(), true)).collect();
        b.outputs = engine.outputs.iter().map(|v| (v.clone(), true)).collect();
        b.rules = engine
            .rules
            .iter()
            .map(|r| RuleSource::Built(r.clone()))
            .collect();
        b
    }
}

impl<T: Real> Engine<T> {
    /// The same engine with every integral / maximum defuzzifier at `resolution` (e.g. an
    /// imported 101-sample MATLAB engine switched to [`Resolution::Exact`]).
    pub fn with_resolution(&self, resolution: Resolution) -> Result<Engine<T>, BuildError> {
        let mut b = EngineBuilder::from(self);
        for (v, _) in &mut b.outputs {
            v.defuzzifier = match v.defuzzifier {
                Defuzzifier::Centroid(_) => Defuzzifier::Centroid(resolution),
                Defuzzifier::Bisector(_) => Defuzzifier::Bisector(resolution),
                Defuzzifier::MeanOfMaximum(_) => Defuzzifier::MeanOfMaximum(resolution),
                Defuzzifier::SmallestOfMaximum(_) => Defuzzifier::SmallestOfMaximum(resolution),
                Defuzzifier::LargestOfMaximum(_) => Defuzzifier::LargestOfMaximum(resolution),
                d @ (Defuzzifier::CenterAverage | Defuzzifier::WeightedAverage) => d,
            };
        }
        b.build()
    }
}
