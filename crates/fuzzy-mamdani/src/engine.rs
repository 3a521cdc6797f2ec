//! The built engine: immutable, evaluated with caller-owned scratch space.

use alloc::string::String;
use alloc::vec::Vec;

use crate::activation;
use crate::defuzz::{self, Grid, PieceStats, Statistic};
use crate::exact::{self, Act, Frame};
use crate::rules::{self, Op};
use crate::{
    Activation, Defuzzifier, EvalError, Hedges, InputVariable, Mf, OutOfRange, OutputVariable,
    Real, Rule, RuleBlock, SNorm, TNorm,
};

/// A Mamdani fuzzy inference engine, built by [`crate::EngineBuilder`] or imported from a
/// `.fis` / `.fll` file.
///
/// Evaluation takes `&self` and a [`Scratch`] made once by [`Engine::scratch`]: one engine can be
/// shared by threads each holding its own scratch, and no evaluation allocates.
///
/// ```
/// use fuzzy_mamdani::{Defuzzifier, EngineBuilder, Mf, Resolution};
///
/// let engine = EngineBuilder::<f64>::new("heater")
///     .input("temp", 0.0, 40.0, [("cold", Mf::Trapezoid { a: 0.0, b: 0.0, c: 10.0, d: 20.0 }),
///                                 ("hot", Mf::Trapezoid { a: 15.0, b: 30.0, c: 40.0, d: 40.0 })])
///     .output("power", 0.0, 1.0, [("low", Mf::Triangle { a: 0.0, b: 0.0, c: 0.5 }),
///                                  ("high", Mf::Triangle { a: 0.5, b: 1.0, c: 1.0 })])
///     .defuzzifier(Defuzzifier::Centroid(Resolution::Exact))
///     .rule("if temp is cold then power is high")
///     .rule("if temp is hot then power is low")
///     .build()?;
/// let mut scratch = engine.scratch();
/// let cold = engine.evaluate(&mut scratch, &[5.0])?[0];
/// let hot = engine.evaluate(&mut scratch, &[35.0])?[0];
/// assert!(cold > 0.8 && hot < 0.2);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct Engine<T> {
    pub(crate) name: String,
    pub(crate) inputs: Vec<InputVariable<T>>,
    pub(crate) outputs: Vec<OutputVariable<T>>,
    pub(crate) rules: Vec<Rule<T>>,
    /// At least one; together they hold every rule, in order.
    pub(crate) blocks: Vec<RuleBlock<T>>,
    pub(crate) activation_threshold: T,
    pub(crate) compiled: Compiled<T>,
}

/// What [`crate::EngineBuilder::build`] precomputes for evaluation.
#[derive(Debug, Clone)]
pub(crate) struct Compiled<T> {
    /// Flat input-term index where each input's terms start; one extra entry at the end.
    pub(crate) input_offsets: Vec<usize>,
    /// All input membership functions, flat.
    pub(crate) input_mfs: Vec<Mf<T>>,
    /// A chained engine's ([`crate::Expr::Output`]): where each output's terms' conclusions
    /// so far start in the scratch degrees, after the input terms; one extra entry at the end.
    pub(crate) output_offsets: Option<Vec<usize>>,
    pub(crate) ops: Vec<Op>,
    /// `ops[start..end]` of each rule.
    pub(crate) rule_ops: Vec<(u32, u32)>,
    /// When every rule is `a and b` (no NOT): the rules indexed by their first membership.
    pub(crate) and_index: Option<AndIndex>,
    pub(crate) weights: Vec<T>,
    /// The implication of each rule's block.
    pub(crate) implications: Vec<TNorm>,
    /// The one implication of every block, if they share it.
    pub(crate) implication: Option<TNorm>,
    pub(crate) plans: Vec<OutputPlan<T>>,
    pub(crate) shape: ScratchShape,
}

/// Rules of the form `a and b`, grouped by `a`: `entries[offsets[a]..offsets[a + 1]]` holds
/// `(b, rule)` for every rule whose first membership is `a`. Every T-norm gives 0 when either
/// side is 0, so a rule with a zero membership on either side has zero strength exactly and is
/// never visited: with triangles or trapezoids only a few terms per input are non-zero.
#[derive(Debug, Clone)]
pub(crate) struct AndIndex {
    pub(crate) offsets: Vec<u32>,
    pub(crate) entries: Vec<(u32, u32)>,
}

/// One conclusion on an output: `(rule, term, negated, hedges)`.
pub(crate) type Conclusion = (u32, u32, bool, Hedges);

/// Per output: its consequents and what its defuzzifier precomputes.
#[derive(Debug, Clone)]
pub(crate) struct OutputPlan<T> {
    pub(crate) mfs: Vec<Mf<T>>,
    /// Centre of each term for the averaging defuzzifiers.
    pub(crate) centers: Vec<T>,
    /// `(rule, term, negated, hedges)` of every consequent on this output, in rule order.
    pub(crate) consequents: Vec<Conclusion>,
    /// Whether a consequent has hedges (the evaluation is then the general one).
    pub(crate) hedged: bool,
    /// `consequents[rule_offsets[r]..rule_offsets[r + 1]]` are rule `r`'s.
    pub(crate) rule_offsets: Vec<u32>,
    pub(crate) stat: Option<Statistic>,
    /// Sample count of the sampled path, 0 otherwise.
    pub(crate) samples: usize,
    /// Where the samples are.
    pub(crate) grid: Grid<T>,
    /// μ of each term at each sample, term-major: input independent, so computed once.
    pub(crate) table: Vec<T>,
}

/// The buffer sizes an engine needs; a [`Scratch`] remembers the shape it was made for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct ScratchShape {
    pub(crate) input_terms: usize,
    /// Output terms whose conclusions so far a chained engine's rules read (0 otherwise).
    pub(crate) output_terms: usize,
    pub(crate) rules: usize,
    pub(crate) acts: usize,
    pub(crate) levels: usize,
    pub(crate) samples: usize,
    pub(crate) outputs: usize,
}

/// Working memory for one evaluation at a time, made by [`Engine::scratch`].
///
/// Its buffers are sized for the engine once, so evaluating never allocates.
#[derive(Debug, Clone)]
pub struct Scratch<T> {
    shape: ScratchShape,
    mu: Vec<T>,
    strength: Vec<T>,
    work: Work<T>,
    out: Vec<T>,
}

/// The parts of [`Scratch`] that firing and defuzzifying write beside the strengths.
#[derive(Debug, Clone)]
struct Work<T> {
    /// Rules with non-zero strength, ascending (filled on the AND-pairs path only).
    fired: Vec<u32>,
    acts: Vec<Act<T>>,
    levels: Vec<T>,
    agg: Vec<T>,
    points: Vec<T>,
    lines: Vec<(T, T)>,
}

impl<T: Real> Engine<T> {
    /// The engine's name.
    pub fn name(&self) -> &str {
        &self.name
    }
    /// The input variables, in order.
    pub fn inputs(&self) -> &[InputVariable<T>] {
        &self.inputs
    }
    /// The output variables, in order.
    pub fn outputs(&self) -> &[OutputVariable<T>] {
        &self.outputs
    }
    /// The rules, in order.
    pub fn rules(&self) -> &[Rule<T>] {
        &self.rules
    }
    /// The rule blocks, in order (one unless built with
    /// [`crate::EngineBuilder::rule_block`] or read from a file with several).
    pub fn rule_blocks(&self) -> &[RuleBlock<T>] {
        &self.blocks
    }
    /// The T-norm joining `and`ed propositions (of the first rule block).
    pub fn conjunction(&self) -> TNorm {
        self.blocks[0].conjunction
    }
    /// The S-norm joining `or`ed propositions (of the first rule block).
    pub fn disjunction(&self) -> SNorm {
        self.blocks[0].disjunction
    }
    /// The T-norm shaping a consequent term by its rule's strength (of the first rule block).
    pub fn implication(&self) -> TNorm {
        self.blocks[0].implication
    }
    /// The activation method of the rules (of the first rule block; fuzzylite's
    /// `activation:`).
    pub fn activation(&self) -> Activation<T> {
        self.blocks[0].activation
    }
    /// A conclusion takes part only when its activation degree (the rule's weighted strength,
    /// hedged) is above this; see [`crate::EngineBuilder::activation_threshold`].
    pub fn activation_threshold(&self) -> T {
        self.activation_threshold
    }

    /// Scratch space sized for this engine (the only allocation evaluation needs).
    pub fn scratch(&self) -> Scratch<T> {
        let s = self.compiled.shape;
        Scratch {
            shape: s,
            mu: alloc::vec![T::zero(); s.input_terms + s.output_terms],
            strength: alloc::vec![T::zero(); s.rules],
            work: Work {
                fired: Vec::with_capacity(s.rules),
                acts: Vec::with_capacity(s.acts),
                levels: alloc::vec![T::zero(); s.levels],
                agg: alloc::vec![T::zero(); s.samples],
                points: Vec::with_capacity(s.acts * exact::POINTS_PER_ACT + 2),
                lines: Vec::with_capacity(s.acts),
            },
            out: alloc::vec![T::zero(); s.outputs],
        }
    }

    /// Evaluates the engine: one crisp value per output, in output order.
    ///
    /// Inputs outside their universe follow each input's [`OutOfRange`] policy; a NaN or
    /// infinite input is an error (except ±∞ under [`OutOfRange::Clamp`], which saturates).
    /// An output for which no rule fires takes its declared default, or is
    /// [`EvalError::NoRuleFired`]: never a silent NaN.
    pub fn evaluate<'s>(
        &self,
        scratch: &'s mut Scratch<T>,
        inputs: &[T],
    ) -> Result<&'s [T], EvalError> {
        let c = &self.compiled;
        if scratch.shape != c.shape {
            return Err(EvalError::ScratchMismatch);
        }
        if inputs.len() != self.inputs.len() {
            return Err(EvalError::InputCount {
                expected: self.inputs.len(),
                got: inputs.len(),
            });
        }
        for (i, (var, &x)) in self.inputs.iter().zip(inputs).enumerate() {
            let x = admit(var, x, i)?;
            let (lo, hi) = (c.input_offsets[i], c.input_offsets[i + 1]);
            for (m, mf) in scratch.mu[lo..hi].iter_mut().zip(&c.input_mfs[lo..hi]) {
                *m = mf.membership(x);
            }
        }
        self.fire(scratch);
        for (o, plan) in c.plans.iter().enumerate() {
            let var = &self.outputs[o];
            let value = self.defuzzify(var, plan, scratch);
            scratch.out[o] = match value.or(var.default) {
                Some(v) => v,
                None => return Err(EvalError::NoRuleFired { output: o }),
            };
        }
        Ok(&scratch.out)
    }

    /// Every rule's weighted firing strength into `scratch.strength`.
    fn fire(&self, scratch: &mut Scratch<T>) {
        let c = &self.compiled;
        if let Some(offsets) = &c.output_offsets {
            return self.fire_chained(scratch, offsets);
        }
        let Scratch {
            mu,
            strength,
            work: Work { fired, .. },
            ..
        } = scratch;
        if let Some(index) = &c.and_index {
            // All rules are `a and b`: visit only pairs whose memberships are both non-zero.
            strength.fill(T::zero());
            fired.clear();
            for (a, &ma) in mu.iter().enumerate() {
                if ma == T::zero() {
                    continue;
                }
                let (lo, hi) = (index.offsets[a] as usize, index.offsets[a + 1] as usize);
                for &(b, r) in &index.entries[lo..hi] {
                    let mb = mu.get(b as usize).copied().unwrap_or_else(T::zero);
                    if mb == T::zero() {
                        continue;
                    }
                    let t = match self.blocks[0].conjunction {
                        TNorm::Minimum => ma.min(mb),
                        TNorm::AlgebraicProduct => ma * mb,
                        t => t.apply(ma, mb),
                    };
                    strength[r as usize] = c.weights[r as usize] * t;
                    fired.push(r);
                }
            }
            // Ascending, so sums over fired rules add in the same order as over all rules.
            fired.sort_unstable();
            return;
        }
        for block in &self.blocks {
            let rules = block.rules.clone();
            for r in rules.clone() {
                let (lo, hi) = c.rule_ops[r];
                let ops = &c.ops[lo as usize..hi as usize];
                strength[r] =
                    c.weights[r] * rules::eval_ops(ops, mu, block.conjunction, block.disjunction);
            }
            block.activation.apply(&mut strength[rules], fired);
        }
    }

    /// [`Self::fire`] for a chained engine: block by block, each rule's conclusions are
    /// aggregated into the output-term degrees after the input memberships as soon as its
    /// block's activation method triggers it, so that later rules read them (pyfuzzylite's
    /// `Engine.process`: outputs cleared, then each block's `activate`).
    fn fire_chained(&self, scratch: &mut Scratch<T>, offsets: &[usize]) {
        let c = &self.compiled;
        let Scratch {
            mu,
            strength,
            work: Work { fired, .. },
            ..
        } = scratch;
        mu[c.shape.input_terms..].fill(T::zero());
        for block in &self.blocks {
            let rules = block.rules.clone();
            let degree = |r: usize, mu: &[T]| {
                let (lo, hi) = c.rule_ops[r];
                let ops = &c.ops[lo as usize..hi as usize];
                c.weights[r] * rules::eval_ops(ops, mu, block.conjunction, block.disjunction)
            };
            match block.activation.rule_by_rule() {
                Some(backwards) => {
                    let mut taken = 0;
                    let mut visit = |r: usize| {
                        let d = degree(r, mu);
                        if block.activation.triggers(d, &mut taken) {
                            strength[r] = d;
                            self.conclude(r, d, mu, offsets);
                        } else {
                            strength[r] = activation::untriggered();
                        }
                    };
                    if backwards {
                        rules.rev().for_each(&mut visit);
                    } else {
                        rules.for_each(&mut visit);
                    }
                }
                None => {
                    for r in rules.clone() {
                        strength[r] = degree(r, mu);
                    }
                    block.activation.apply(&mut strength[rules.clone()], fired);
                    for r in rules {
                        self.conclude(r, strength[r], mu, offsets);
                    }
                }
            }
        }
    }

    /// Aggregates rule `r`'s conclusions at activation degree `d` into the output-term
    /// degrees of `mu` (one taking part in defuzzification: hedged, above the threshold).
    fn conclude(&self, r: usize, d: T, mu: &mut [T], offsets: &[usize]) {
        for c in &self.rules[r].consequents {
            let w = c.hedges.apply(d);
            if w > self.activation_threshold {
                let slot = &mut mu[offsets[c.output] + c.term];
                *slot = self.outputs[c.output].aggregation.apply(*slot, w);
            }
        }
    }

    fn defuzzify(
        &self,
        var: &OutputVariable<T>,
        plan: &OutputPlan<T>,
        s: &mut Scratch<T>,
    ) -> Option<T> {
        let Scratch { strength, work, .. } = s;
        let strength: &[T] = strength;
        // A conclusion's activation degree: its rule's strength, hedged. Monomorphised twice
        // so that engines without hedged conclusions pay nothing for them.
        if plan.hedged {
            self.defuzzify_with(var, plan, work, |&(r, _, _, h)| {
                h.apply(strength[r as usize])
            })
        } else {
            self.defuzzify_with(var, plan, work, |&(r, _, _, _)| strength[r as usize])
        }
    }

    /// Calls `f` on an output's conclusions that can have fired: silent rules add 0 to any
    /// sum, so where the fired rules are known (no hedged conclusion then) only theirs.
    #[inline(always)]
    fn visit_conclusions(
        &self,
        plan: &OutputPlan<T>,
        fired_rules: &[u32],
        mut f: impl FnMut(&Conclusion),
    ) {
        if self.compiled.and_index.is_some() {
            for &r in fired_rules {
                let (lo, hi) = (
                    plan.rule_offsets[r as usize],
                    plan.rule_offsets[r as usize + 1],
                );
                plan.consequents[lo as usize..hi as usize]
                    .iter()
                    .for_each(&mut f);
            }
        } else {
            plan.consequents.iter().for_each(f);
        }
    }

    #[inline(always)]
    fn defuzzify_with(
        &self,
        var: &OutputVariable<T>,
        plan: &OutputPlan<T>,
        s: &mut Work<T>,
        degree: impl Fn(&Conclusion) -> T + Copy,
    ) -> Option<T> {
        let Work {
            fired: fired_rules,
            acts,
            levels,
            agg,
            points,
            lines,
        } = s;
        let threshold = self.activation_threshold;
        if var.defuzzifier == Defuzzifier::CenterAverage {
            // A select, not a branch: below the threshold is weight 0.
            let weight = |c: &Conclusion| {
                let w = degree(c);
                if w > threshold { w } else { T::zero() }
            };
            let (mut num, mut den) = (T::zero(), T::zero());
            self.visit_conclusions(plan, fired_rules, |c| {
                let w = weight(c);
                num = num + w * plan.centers[c.1 as usize];
                den = den + w;
            });
            // Where Σ w c overflowed: the weights normalised, the centres halved.
            let halved = || {
                let mut n = T::zero();
                self.visit_conclusions(plan, fired_rules, |c| {
                    n = n + weight(c) / den * (plan.centers[c.1 as usize] * T::of(0.5))
                });
                n
            };
            return weighted_mean(num, den, halved);
        }
        let fired = plan
            .consequents
            .iter()
            .map(|c| (c, degree(c)))
            .filter(|(_, w)| *w > threshold);
        // Per term (and its complement) the aggregation of its rules' strengths.
        let levels = &mut levels[..2 * plan.mfs.len()];
        levels.fill(T::zero());
        for (&(_, t, neg, _), w) in fired.clone() {
            let slot = &mut levels[2 * t as usize + usize::from(neg)];
            *slot = var.aggregation.apply(*slot, w);
        }
        if var.defuzzifier == Defuzzifier::WeightedAverage {
            let (mut num, mut den) = (T::zero(), T::zero());
            for (t, h) in levels.chunks_exact(2).enumerate() {
                num = num + h[0] * plan.centers[t];
                den = den + h[0];
            }
            let halved = || {
                let terms = levels.chunks_exact(2).zip(&plan.centers);
                terms.fold(T::zero(), |n, (h, &c)| n + h[0] / den * (c * T::of(0.5)))
            };
            return weighted_mean(num, den, halved);
        }
        acts.clear();
        let c = &self.compiled;
        match (var.aggregation, c.implication) {
            // max_r I(w_r, μ) = I(max_r w_r, μ) for any T-norm I: one activation per term
            // (when every block implies alike).
            (SNorm::Maximum, Some(imp)) => {
                let nonzero = levels.iter().enumerate().filter(|(_, w)| **w > T::zero());
                acts.extend(nonzero.map(|(k, &w)| Act {
                    term: (k / 2) as u32,
                    negated: k % 2 == 1,
                    w,
                    imp,
                }));
            }
            _ => acts.extend(fired.map(|(&(r, term, negated, _), w)| Act {
                term,
                negated,
                w,
                imp: c.implications[r as usize],
            })),
        }
        let stat = plan.stat?;
        if plan.samples > 0 {
            let agg = &mut agg[..plan.samples];
            accumulate(agg, acts, &plan.table, var.aggregation);
            return defuzz::sampled(stat, agg, &plan.grid);
        }
        let (aggr, range) = (var.aggregation, (var.min, var.max));
        let mut walk = |visit: &mut dyn FnMut(T, T, T, T)| {
            exact::for_each_piece(acts, &plan.mfs, aggr, range, points, lines, visit);
        };
        // The walk is in the universe's frame; answers go back to the universe.
        let frame = Frame::new(var.min, var.max);
        let mut stats = PieceStats::new();
        walk(&mut |a, b, c, d| stats.add(a, b, c, d));
        if stat != Statistic::Bisector {
            return stats.finish(stat).map(|u| frame.x(u));
        }
        if !(stats.area > T::zero()) {
            return None;
        }
        let half = stats.area / (T::one() + T::one());
        let (mut run, mut found) = (T::zero(), None);
        walk(&mut |x0, y0, x1, y1| {
            let piece = (y0 + y1) / (T::one() + T::one()) * (x1 - x0);
            if found.is_none() && run + piece >= half {
                found = Some(defuzz::bisector_in_piece(x0, y0, x1, y1, half - run));
            }
            run = run + piece;
        });
        // Rounding can leave the running sum a hair under `half` at the end: the right end.
        Some(found.map_or(var.max, |u| frame.x(u)))
    }
}

fn admit<T: Real>(var: &InputVariable<T>, x: T, input: usize) -> Result<T, EvalError> {
    admit_to(var.min, var.max, var.out_of_range, x, input)
}

/// Input `input`'s value `x` as evaluation takes it, for a universe `[min, max]` and `policy`.
pub(crate) fn admit_to<T: Real>(
    min: T,
    max: T,
    policy: OutOfRange,
    x: T,
    input: usize,
) -> Result<T, EvalError> {
    if x.is_nan() || (x.is_infinite() && policy != OutOfRange::Clamp) {
        return Err(EvalError::NonFiniteInput { input });
    }
    if x >= min && x <= max {
        return Ok(x);
    }
    match policy {
        OutOfRange::Clamp => Ok(x.max(min).min(max)),
        OutOfRange::Evaluate => Ok(x),
        OutOfRange::Error => Err(EvalError::OutOfRange { input }),
    }
}

/// `num / den` for a positive `den`; where `num` overflowed (centres near the largest float),
/// `2 · halved()`, the mean of the halved centres recomputed with normalised weights.
pub(crate) fn weighted_mean<T: Real>(num: T, den: T, halved: impl FnOnce() -> T) -> Option<T> {
    if !(den > T::zero()) {
        return None;
    }
    let mean = num / den;
    Some(if mean.is_finite() {
        mean
    } else {
        halved() * (T::one() + T::one())
    })
}

/// `agg[k] = S_a I(w_a, μ_a(x_k))` over the activations, from the precomputed term table.
fn accumulate<T: Real>(agg: &mut [T], acts: &[Act<T>], table: &[T], aggr: SNorm) {
    agg.fill(T::zero());
    let n = agg.len();
    for a in acts {
        let Some(row) = table.get(a.term as usize * n..(a.term as usize + 1) * n) else {
            continue;
        };
        let (w, imp) = (a.w, a.imp);
        // The common pairs get their own monomorphic loop so the compiler can vectorise it.
        match (imp, aggr, a.negated) {
            (TNorm::Minimum, SNorm::Maximum, false) => {
                fold(agg, row, |m| w.min(m), |x, y| x.max(y))
            }
            (TNorm::AlgebraicProduct, SNorm::Maximum, false) => {
                fold(agg, row, |m| w * m, |x, y| x.max(y))
            }
            (TNorm::Minimum, SNorm::UnboundedSum, false) => {
                fold(agg, row, |m| w.min(m), |x, y| x + y)
            }
            (_, _, neg) => {
                let m = |m: T| if neg { T::one() - m } else { m };
                fold(agg, row, |v| imp.apply(w, m(v)), |x, y| aggr.apply(x, y));
            }
        }
    }
}

#[inline(always)]
fn fold<T: Copy>(agg: &mut [T], row: &[T], imp: impl Fn(T) -> T, aggr: impl Fn(T, T) -> T) {
    for (g, &m) in agg.iter_mut().zip(row) {
        *g = aggr(*g, imp(m));
    }
}
