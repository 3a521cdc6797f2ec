//! Rules: antecedent expressions, consequents, weights, and the fuzzylite rule syntax.

use alloc::boxed::Box;
use alloc::string::{String, ToString};
use alloc::vec::Vec;
use core::fmt::Write;

use crate::{BuildError, Hedge, Hedges, InputVariable, OutputVariable, Real, SNorm, TNorm};

/// An antecedent: propositions `input is [hedges] term` (and, in a chained engine,
/// `output is [hedges] term`) joined by AND / OR.
///
/// ```
/// use fuzzy_mamdani::{Expr, Hedge, Hedges};
/// // (input 0 is term 2) and not (input 1 is term 0) or input 1 is very term 1
/// let very = Hedges::new(&[Hedge::Very]).expect("one hedge");
/// let e = Expr::is(0, 2).and(Expr::is_not(1, 0)).or(Expr::hedged(1, 1, very));
/// assert_eq!(e.depth(), 2);
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Expr {
    /// `input is hedges term`: the term's membership with the hedges applied, the rightmost
    /// first (`not` alone is the complement `1 − μ`).
    Is {
        /// Input index.
        input: usize,
        /// Term index within that input.
        term: usize,
        /// The hedges as written (empty for `input is term`).
        hedges: Hedges,
    },
    /// `input is hedges any`: holds fully (degree 1) whatever the input, then the hedges
    /// written before `any` apply (`input is not any` is 0), as in fuzzylite.
    Any {
        /// Input index.
        input: usize,
        /// The hedges written before `any`.
        hedges: Hedges,
    },
    /// `output is hedges term` (a chained engine, evaluated as fuzzylite does): the term's
    /// activation degree so far in this evaluation, then the hedges. That degree is the
    /// output's aggregation over the term's conclusions triggered before this rule is
    /// evaluated — by earlier rule blocks and, where the block's [`crate::Activation`] triggers
    /// rule by rule (`General`, `First`, `Threshold` in rule order; `Last` from the end), by
    /// the rules evaluated before it in its block; 0 when there are none. A conclusion counts
    /// with its activation degree (the rule's weighted strength, hedged) when that is above
    /// the engine's activation threshold, as in defuzzification.
    Output {
        /// Output index.
        output: usize,
        /// Term index within that output.
        term: usize,
        /// The hedges as written (empty for `output is term`).
        hedges: Hedges,
    },
    /// Conjunction with the engine's T-norm.
    And(Box<Expr>, Box<Expr>),
    /// Disjunction with the engine's S-norm.
    Or(Box<Expr>, Box<Expr>),
}

impl Expr {
    /// `input is term`.
    pub fn is(input: usize, term: usize) -> Self {
        Expr::hedged(input, term, Hedges::NONE)
    }
    /// `input is not term`.
    pub fn is_not(input: usize, term: usize) -> Self {
        Expr::hedged(input, term, Hedges::NOT)
    }
    /// `input is hedges term`.
    pub fn hedged(input: usize, term: usize, hedges: Hedges) -> Self {
        Expr::Is {
            input,
            term,
            hedges,
        }
    }
    /// `output is hedges term`: a proposition on a conclusion so far (a chained engine).
    pub fn output(output: usize, term: usize, hedges: Hedges) -> Self {
        Expr::Output {
            output,
            term,
            hedges,
        }
    }
    /// `self and other`.
    pub fn and(self, other: Expr) -> Self {
        Expr::And(Box::new(self), Box::new(other))
    }
    /// `self or other`.
    pub fn or(self, other: Expr) -> Self {
        Expr::Or(Box::new(self), Box::new(other))
    }
    /// How many values the postfix evaluation stack holds at most.
    pub fn depth(&self) -> usize {
        match self {
            Expr::Is { .. } | Expr::Any { .. } | Expr::Output { .. } => 1,
            Expr::And(a, b) | Expr::Or(a, b) => a.depth().max(1 + b.depth()),
        }
    }
    /// Whether a proposition reads an output variable (the engine is then chained).
    pub fn reads_outputs(&self) -> bool {
        self.reads_output_where(&|_| true)
    }
    /// Whether a proposition reads an output whose index satisfies `which`.
    pub(crate) fn reads_output_where(&self, which: &impl Fn(usize) -> bool) -> bool {
        match self {
            Expr::Output { output, .. } => which(*output),
            Expr::Is { .. } | Expr::Any { .. } => false,
            Expr::And(a, b) | Expr::Or(a, b) => {
                a.reads_output_where(which) || b.reads_output_where(which)
            }
        }
    }
}

/// `output is [hedges] term` in a rule's conclusion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Consequent {
    /// Output index.
    pub output: usize,
    /// Term index within that output.
    pub term: usize,
    /// Use the complement `1 − μ` of the term (MATLAB's negative output index; no rule text
    /// expresses it).
    pub negated: bool,
    /// Hedges on the rule's activation degree before it implies the term (fuzzylite's
    /// `then y is very B`; `then y is not B` implies `B` with `1 − w`).
    pub hedges: Hedges,
}

impl Consequent {
    /// `output is term`.
    pub fn new(output: usize, term: usize) -> Self {
        Consequent {
            output,
            term,
            negated: false,
            hedges: Hedges::NONE,
        }
    }
}

/// `if antecedent then consequents with weight`.
#[derive(Debug, Clone, PartialEq)]
pub struct Rule<T> {
    /// The condition.
    pub antecedent: Expr,
    /// The conclusions, at most one per output.
    pub consequents: Vec<Consequent>,
    /// Multiplies the firing strength; in `[0, 1]`.
    pub weight: T,
}

/// The deepest antecedent the fixed evaluation stack takes.
pub(crate) const MAX_DEPTH: usize = 16;

/// One step of a compiled (postfix) antecedent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Op {
    /// Push the degree at this flat term index (input memberships, then the outputs'
    /// conclusions so far), hedged.
    Term {
        mu: u32,
        hedges: Hedges,
    },
    /// Push `hedges(1)` (`input is … any`).
    Any {
        hedges: Hedges,
    },
    And,
    Or,
}

/// Compiles `expr` to postfix; `offsets` and `output_offsets` give where each input's and
/// each output's terms start in the flat degrees [`eval_ops`] reads.
pub(crate) fn compile(expr: &Expr, offsets: &[usize], output_offsets: &[usize], out: &mut Vec<Op>) {
    match expr {
        Expr::Is {
            input,
            term,
            hedges,
        } => out.push(Op::Term {
            // Indices were validated before compiling; the total term count fits in u32.
            mu: (offsets[*input] + term) as u32,
            hedges: *hedges,
        }),
        Expr::Output {
            output,
            term,
            hedges,
        } => out.push(Op::Term {
            mu: (output_offsets[*output] + term) as u32,
            hedges: *hedges,
        }),
        Expr::Any { hedges, .. } => out.push(Op::Any { hedges: *hedges }),
        Expr::And(a, b) | Expr::Or(a, b) => {
            compile(a, offsets, output_offsets, out);
            compile(b, offsets, output_offsets, out);
            out.push(if matches!(expr, Expr::And(..)) {
                Op::And
            } else {
                Op::Or
            });
        }
    }
}

/// Runs a compiled antecedent on the fuzzified inputs (and conclusions so far) `mu`.
#[inline]
pub(crate) fn eval_ops<T: Real>(ops: &[Op], mu: &[T], and: TNorm, or: SNorm) -> T {
    let term = |i: u32, hedges: Hedges| {
        let m = mu.get(i as usize).copied().unwrap_or_else(T::zero);
        match hedges {
            Hedges::NONE => m,
            Hedges::NOT => T::one() - m,
            h => h.apply(m),
        }
    };
    // The shapes of nearly every rule (one or two propositions) skip the stack.
    match *ops {
        [Op::Term { mu: a, hedges }] => return term(a, hedges),
        [
            Op::Term { mu: a, hedges: na },
            Op::Term { mu: b, hedges: nb },
            op @ (Op::And | Op::Or),
        ] => {
            let (x, y) = (term(a, na), term(b, nb));
            return if op == Op::And {
                and.apply(x, y)
            } else {
                or.apply(x, y)
            };
        }
        _ => {}
    }
    let mut stack = [T::zero(); MAX_DEPTH];
    let mut top = 0usize;
    for op in ops {
        match *op {
            Op::Term { .. } | Op::Any { .. } => {
                let v = match *op {
                    Op::Term { mu: i, hedges } => term(i, hedges),
                    Op::Any { hedges } => hedges.apply(T::one()),
                    _ => T::zero(),
                };
                if let Some(slot) = stack.get_mut(top) {
                    *slot = v;
                }
                top += 1;
            }
            Op::And | Op::Or if top >= 2 => {
                let (a, b) = (stack[top - 2], stack[top - 1]);
                stack[top - 2] = if *op == Op::And {
                    and.apply(a, b)
                } else {
                    or.apply(a, b)
                };
                top -= 1;
            }
            // Unreachable for compiled expressions (always well formed); harmless otherwise.
            Op::And | Op::Or => {}
        }
    }
    if top == 0 { T::zero() } else { stack[0] }
}

/// Parses a rule in fuzzylite's syntax against the engine's variables.
///
/// `if e is NH and (de is not PB or de is very ZO) then tau is PH and u is somewhat ZO with 0.5`
///
/// `and` binds tighter than `or`; parentheses group; `with w` is optional (default 1). A
/// proposition takes any [`Hedge`]s before its term; `input is any` has no term. A
/// proposition on an output variable makes a chained engine ([`Expr::Output`]). Hedges in a
/// conclusion modify the rule's activation degree (fuzzylite's meaning, see
/// [`Consequent::hedges`]). Errors carry the 1-based column of the offending word.
pub fn parse_rule<T: Real>(
    text: &str,
    index: usize,
    inputs: &[InputVariable<T>],
    outputs: &[OutputVariable<T>],
) -> Result<Rule<T>, BuildError> {
    let tokens = tokenize(text);
    let syntax = |at: Option<&(usize, &str)>, reason| BuildError::RuleSyntax {
        rule: index,
        text: text.to_string(),
        column: at.map_or(text.chars().count() + 1, |t| t.0),
        reason,
    };
    if tokens.first().map(|t| t.1) != Some("if") {
        return Err(syntax(tokens.first(), "`if` at the start"));
    }
    let then = tokens
        .iter()
        .position(|t| t.1 == "then")
        .ok_or_else(|| syntax(None, "`then`"))?;
    let mut p = Parser {
        tokens: &tokens[1..then],
        pos: 0,
        rule: index,
        text,
        inputs,
        outputs,
    };
    let antecedent = p.disjunction()?;
    if p.pos != p.tokens.len() {
        return Err(syntax(p.tokens.get(p.pos), "`and`, `or` or `then`"));
    }
    let mut rest = &tokens[then + 1..];
    let mut weight = T::one();
    if let Some(w) = rest.iter().position(|t| t.1 == "with") {
        let value = rest
            .get(w + 1)
            .ok_or_else(|| syntax(None, "a weight after `with`"))?;
        weight = value
            .1
            .parse::<f64>()
            .map(T::of)
            .map_err(|_| syntax(Some(value), "a number as the weight"))?;
        if let Some(extra) = rest.get(w + 2) {
            return Err(syntax(Some(extra), "the end of the rule after the weight"));
        }
        rest = &rest[..w];
    }
    let mut consequents = Vec::new();
    for clause in rest.split(|t| t.1 == "and") {
        let [name, is, words @ ..] = clause else {
            return Err(syntax(
                clause.first(),
                "a conclusion `output is [hedges] term`",
            ));
        };
        if is.1 != "is" {
            return Err(syntax(Some(is), "`is`"));
        }
        let (hedges, term) = hedges_and_term(words).map_err(|(at, reason)| match at {
            Some(w) if reason == UNKNOWN_HEDGE => unknown(index, "hedge", w.1),
            at => syntax(at.or_else(|| clause.last()), reason),
        })?;
        let term = term.ok_or_else(|| syntax(Some(name), "a term, not `any`, in a conclusion"))?;
        let output = outputs
            .iter()
            .position(|o| o.name == name.1)
            .ok_or_else(|| unknown(index, "output", name.1))?;
        let term = outputs[output]
            .terms
            .iter()
            .position(|t| t.name == term.1)
            .ok_or_else(|| unknown(index, "term", term.1))?;
        consequents.push(Consequent {
            output,
            term,
            negated: false,
            hedges,
        });
    }
    Ok(Rule {
        antecedent,
        consequents,
        weight,
    })
}

/// The words of a rule with their 1-based columns; parentheses are words of their own.
fn tokenize(text: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut start: Option<(usize, usize)> = None;
    let mut column = 0;
    for (byte, ch) in text.char_indices() {
        column += 1;
        let split = ch.is_whitespace() || ch == '(' || ch == ')';
        if split {
            if let Some((col, from)) = start.take() {
                out.push((col, &text[from..byte]));
            }
            if ch != ' ' && !ch.is_whitespace() {
                out.push((column, &text[byte..byte + 1]));
            }
        } else if start.is_none() {
            start = Some((column, byte));
        }
    }
    if let Some((col, from)) = start {
        out.push((col, &text[from..]));
    }
    out
}

type Word<'a> = (usize, &'a str);

/// Where [`hedges_and_term`] stopped (the word, `None` at the end) and what it expected.
type WordError<'a, 'w> = (Option<&'w Word<'a>>, &'static str);

/// The reason [`hedges_and_term`] gives for a word that is neither a hedge nor the last.
const UNKNOWN_HEDGE: &str = "a hedge";

/// Splits `[hedge…] term` (or `[hedge…] any`) into the hedges and the term word (`None` after
/// `any`); the error names the word and what was expected instead.
fn hedges_and_term<'a, 'w>(
    words: &'w [Word<'a>],
) -> Result<(Hedges, Option<&'w Word<'a>>), WordError<'a, 'w>> {
    let mut list = [Hedge::Not; Hedges::MAX];
    let mut n = 0;
    for (k, w) in words.iter().enumerate() {
        let last = k + 1 == words.len();
        match Hedge::from_name(w.1) {
            Some(Hedge::Any) if last => {
                let hedges = Hedges::new(&list[..n]).ok_or((Some(w), "at most 10 hedges"))?;
                return Ok((hedges, None));
            }
            Some(Hedge::Any) => return Err((words.get(k + 1), "nothing after `any`")),
            Some(h) if !last => {
                *list.get_mut(n).ok_or((Some(w), "at most 10 hedges"))? = h;
                n += 1;
            }
            _ if last => {
                let hedges = Hedges::new(&list[..n]).ok_or((Some(w), "at most 10 hedges"))?;
                return Ok((hedges, Some(w)));
            }
            // A word before the last that is not a hedge: an unknown hedge (fuzzylite's reading).
            _ => return Err((Some(w), UNKNOWN_HEDGE)),
        }
    }
    Err((None, "a term after `is`"))
}

fn unknown(rule: usize, what: &'static str, name: &str) -> BuildError {
    BuildError::Unknown {
        rule,
        what,
        name: name.to_string(),
    }
}

struct Parser<'a, 't, T> {
    tokens: &'t [Word<'a>],
    pos: usize,
    rule: usize,
    text: &'a str,
    inputs: &'t [InputVariable<T>],
    outputs: &'t [OutputVariable<T>],
}

impl<'a, 't, T> Parser<'a, 't, T> {
    fn err(&self, at: usize, reason: &'static str) -> BuildError {
        BuildError::RuleSyntax {
            rule: self.rule,
            text: self.text.to_string(),
            column: self
                .tokens
                .get(at)
                .map_or_else(|| column_after(self.tokens, self.text), |t| t.0),
            reason,
        }
    }
    fn peek(&self) -> Option<&'a str> {
        self.tokens.get(self.pos).map(|t| t.1)
    }
    fn disjunction(&mut self) -> Result<Expr, BuildError> {
        let mut e = self.conjunction()?;
        while self.peek() == Some("or") {
            self.pos += 1;
            e = e.or(self.conjunction()?);
        }
        Ok(e)
    }
    fn conjunction(&mut self) -> Result<Expr, BuildError> {
        let mut e = self.atom()?;
        while self.peek() == Some("and") {
            self.pos += 1;
            e = e.and(self.atom()?);
        }
        Ok(e)
    }
    fn atom(&mut self) -> Result<Expr, BuildError> {
        if self.peek() == Some("(") {
            self.pos += 1;
            let e = self.disjunction()?;
            if self.peek() != Some(")") {
                return Err(self.err(self.pos, "`)`"));
            }
            self.pos += 1;
            return Ok(e);
        }
        let Some(name) = self.peek() else {
            return Err(self.err(self.pos, "a proposition `input is [hedges] term`"));
        };
        if self.tokens.get(self.pos + 1).map(|t| t.1) != Some("is") {
            return Err(self.err(self.pos + 1, "`is`"));
        }
        let start = self.pos + 2;
        // The proposition's words run to the next operator, parenthesis or the end.
        let end = self.tokens[start.min(self.tokens.len())..]
            .iter()
            .position(|t| matches!(t.1, "and" | "or" | "(" | ")"))
            .map_or(self.tokens.len(), |k| start + k);
        let words = &self.tokens[start.min(end)..end];
        let (hedges, term) = hedges_and_term(words).map_err(|(at, reason)| {
            if let (Some(w), UNKNOWN_HEDGE) = (at, reason) {
                return unknown(self.rule, "hedge", w.1);
            }
            let at = at.map_or(end, |w| {
                self.tokens
                    .iter()
                    .position(|t| core::ptr::eq(t, w))
                    .unwrap_or(end)
            });
            self.err(at, reason)
        })?;
        self.pos = end;
        let Some(input) = self.inputs.iter().position(|v| v.name == name) else {
            let output = self
                .outputs
                .iter()
                .position(|v| v.name == name)
                .ok_or_else(|| unknown(self.rule, "variable", name))?;
            let term = term
                .ok_or_else(|| self.err(end - 1, "a term, not `any`, after an output variable"))?;
            let term = self.outputs[output]
                .terms
                .iter()
                .position(|t| t.name == term.1)
                .ok_or_else(|| unknown(self.rule, "term", term.1))?;
            return Ok(Expr::Output {
                output,
                term,
                hedges,
            });
        };
        let Some(term) = term else {
            return Ok(Expr::Any { input, hedges });
        };
        let term = self.inputs[input]
            .terms
            .iter()
            .position(|t| t.name == term.1)
            .ok_or_else(|| unknown(self.rule, "term", term.1))?;
        Ok(Expr::Is {
            input,
            term,
            hedges,
        })
    }
}

/// The column just past the last word (an error at the end of the text).
fn column_after(tokens: &[Word<'_>], text: &str) -> usize {
    tokens
        .last()
        .map_or(text.chars().count() + 1, |t| t.0 + t.1.chars().count())
}

/// Writes a rule in fuzzylite's syntax (the inverse of [`parse_rule`]).
///
/// A complemented conclusion ([`Consequent::negated`], MATLAB's negative index) has no rule
/// text; it is written as its term alone ([`crate::to_fll`] refuses such engines).
pub fn rule_text<T: Real>(
    rule: &Rule<T>,
    inputs: &[InputVariable<T>],
    outputs: &[OutputVariable<T>],
) -> String {
    let mut s = String::from("if ");
    write_expr(&mut s, &rule.antecedent, inputs, outputs, true);
    s.push_str(" then ");
    for (i, c) in rule.consequents.iter().enumerate() {
        if i > 0 {
            s.push_str(" and ");
        }
        let o = &outputs[c.output];
        let _ = write!(s, "{} is ", o.name);
        write_hedges(&mut s, c.hedges);
        let _ = write!(s, "{}", o.terms[c.term].name);
    }
    if rule.weight != T::one() {
        let _ = write!(s, " with {}", rule.weight);
    }
    s
}

fn write_expr<T>(
    s: &mut String,
    e: &Expr,
    inputs: &[InputVariable<T>],
    outputs: &[OutputVariable<T>],
    top: bool,
) {
    match e {
        Expr::Is {
            input,
            term,
            hedges,
        } => {
            let v = &inputs[*input];
            write_proposition(s, &v.name, *hedges, &v.terms[*term].name);
        }
        Expr::Output {
            output,
            term,
            hedges,
        } => {
            let v = &outputs[*output];
            write_proposition(s, &v.name, *hedges, &v.terms[*term].name);
        }
        Expr::Any { input, hedges } => {
            let _ = write!(s, "{} is ", inputs[*input].name);
            write_hedges(s, *hedges);
            s.push_str("any");
        }
        Expr::And(a, b) | Expr::Or(a, b) => {
            // Parenthesise every nested operation: unambiguous whatever the reader's precedence.
            if !top {
                s.push('(');
            }
            write_expr(s, a, inputs, outputs, false);
            s.push_str(if matches!(e, Expr::And(..)) {
                " and "
            } else {
                " or "
            });
            write_expr(s, b, inputs, outputs, false);
            if !top {
                s.push(')');
            }
        }
    }
}

/// `variable is [hedges] term`.
fn write_proposition(s: &mut String, variable: &str, hedges: Hedges, term: &str) {
    let _ = write!(s, "{variable} is ");
    write_hedges(s, hedges);
    s.push_str(term);
}

fn write_hedges(s: &mut String, hedges: Hedges) {
    for h in hedges.iter() {
        s.push_str(h.name());
        s.push(' ');
    }
}
