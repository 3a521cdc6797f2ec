//! Rules: antecedent expressions, consequents, weights, and the fuzzylite rule syntax.

use alloc::boxed::Box;
use alloc::string::{String, ToString};
use alloc::vec::Vec;
use core::fmt::Write;

use crate::{BuildError, InputVariable, OutputVariable, Real, SNorm, TNorm};

/// An antecedent: propositions `input is [not] term` joined by AND / OR.
///
/// ```
/// use fuzzy_mamdani::Expr;
/// // (input 0 is term 2) and not (input 1 is term 0)
/// let e = Expr::is(0, 2).and(Expr::is_not(1, 0));
/// assert_eq!(e.depth(), 2);
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Expr {
    /// `input is term`, or its complement `1 − μ` when `negated`.
    Is {
        /// Input index.
        input: usize,
        /// Term index within that input.
        term: usize,
        /// `is not`.
        negated: bool,
    },
    /// Conjunction with the engine's T-norm.
    And(Box<Expr>, Box<Expr>),
    /// Disjunction with the engine's S-norm.
    Or(Box<Expr>, Box<Expr>),
}

impl Expr {
    /// `input is term`.
    pub fn is(input: usize, term: usize) -> Self {
        Expr::Is {
            input,
            term,
            negated: false,
        }
    }
    /// `input is not term`.
    pub fn is_not(input: usize, term: usize) -> Self {
        Expr::Is {
            input,
            term,
            negated: true,
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
            Expr::Is { .. } => 1,
            Expr::And(a, b) | Expr::Or(a, b) => a.depth().max(1 + b.depth()),
        }
    }
}

/// `output is [not] term` in a rule's conclusion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Consequent {
    /// Output index.
    pub output: usize,
    /// Term index within that output.
    pub term: usize,
    /// Use the complement `1 − μ` of the term (MATLAB's negative output index).
    pub negated: bool,
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
    /// Push the membership at this flat input-term index (or its complement).
    Term {
        mu: u32,
        negated: bool,
    },
    And,
    Or,
}

pub(crate) fn compile(expr: &Expr, offsets: &[usize], out: &mut Vec<Op>) {
    match expr {
        Expr::Is {
            input,
            term,
            negated,
        } => out.push(Op::Term {
            // Indices were validated before compiling; the total term count fits in u32.
            mu: (offsets[*input] + term) as u32,
            negated: *negated,
        }),
        Expr::And(a, b) | Expr::Or(a, b) => {
            compile(a, offsets, out);
            compile(b, offsets, out);
            out.push(if matches!(expr, Expr::And(..)) {
                Op::And
            } else {
                Op::Or
            });
        }
    }
}

/// Runs a compiled antecedent on the fuzzified inputs `mu`.
#[inline]
pub(crate) fn eval_ops<T: Real>(ops: &[Op], mu: &[T], and: TNorm, or: SNorm) -> T {
    let term = |i: u32, negated: bool| {
        let m = mu.get(i as usize).copied().unwrap_or_else(T::zero);
        if negated { T::one() - m } else { m }
    };
    // The shapes of nearly every rule (one or two propositions) skip the stack.
    match *ops {
        [Op::Term { mu: a, negated }] => return term(a, negated),
        [
            Op::Term { mu: a, negated: na },
            Op::Term { mu: b, negated: nb },
            op,
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
            Op::Term { mu: i, negated } => {
                if let Some(slot) = stack.get_mut(top) {
                    *slot = term(i, negated);
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
/// `if e is NH and (de is not PB or de is ZO) then tau is PH and u is ZO with 0.5`
///
/// `and` binds tighter than `or`; parentheses group; `with w` is optional (default 1).
/// Hedges other than `not` are not supported.
pub fn parse_rule<T: Real>(
    text: &str,
    index: usize,
    inputs: &[InputVariable<T>],
    outputs: &[OutputVariable<T>],
) -> Result<Rule<T>, BuildError> {
    let syntax = |reason| BuildError::RuleSyntax {
        rule: index,
        text: text.to_string(),
        reason,
    };
    let spaced = text.replace('(', " ( ").replace(')', " ) ");
    let tokens: Vec<&str> = spaced.split_whitespace().collect();
    if tokens.first() != Some(&"if") {
        return Err(syntax("a rule starts with `if`"));
    }
    let then = tokens
        .iter()
        .position(|t| *t == "then")
        .ok_or_else(|| syntax("missing `then`"))?;
    let mut p = Parser {
        tokens: &tokens[1..then],
        pos: 0,
        rule: index,
        text,
        inputs,
    };
    let antecedent = p.disjunction()?;
    if p.pos != p.tokens.len() {
        return Err(syntax("unexpected token in the antecedent"));
    }
    let mut rest = &tokens[then + 1..];
    let mut weight = T::one();
    if let Some(w) = rest.iter().position(|t| *t == "with") {
        let value = rest
            .get(w + 1)
            .ok_or_else(|| syntax("missing weight after `with`"))?;
        weight = value
            .parse::<f64>()
            .map(T::of)
            .map_err(|_| syntax("weight is not a number"))?;
        if rest.len() != w + 2 {
            return Err(syntax("unexpected token after the weight"));
        }
        rest = &rest[..w];
    }
    let mut consequents = Vec::new();
    for clause in rest.split(|t| *t == "and") {
        let (name, negated, term) = match clause {
            [v, "is", t] => (*v, false, *t),
            [v, "is", "not", t] => (*v, true, *t),
            _ => return Err(syntax("a consequent is `output is [not] term`")),
        };
        let output = outputs
            .iter()
            .position(|o| o.name == name)
            .ok_or_else(|| unknown(index, "output", name))?;
        let term = outputs[output]
            .terms
            .iter()
            .position(|t| t.name == term)
            .ok_or_else(|| unknown(index, "term", term))?;
        consequents.push(Consequent {
            output,
            term,
            negated,
        });
    }
    Ok(Rule {
        antecedent,
        consequents,
        weight,
    })
}

fn unknown(rule: usize, what: &'static str, name: &str) -> BuildError {
    BuildError::Unknown {
        rule,
        what,
        name: name.to_string(),
    }
}

struct Parser<'a, T> {
    tokens: &'a [&'a str],
    pos: usize,
    rule: usize,
    text: &'a str,
    inputs: &'a [InputVariable<T>],
}

impl<'a, T> Parser<'a, T> {
    fn err(&self, reason: &'static str) -> BuildError {
        BuildError::RuleSyntax {
            rule: self.rule,
            text: self.text.to_string(),
            reason,
        }
    }
    fn peek(&self) -> Option<&'a str> {
        self.tokens.get(self.pos).copied()
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
                return Err(self.err("unbalanced parenthesis"));
            }
            self.pos += 1;
            return Ok(e);
        }
        let name = self
            .peek()
            .ok_or_else(|| self.err("expected a proposition"))?;
        if self.tokens.get(self.pos + 1) != Some(&"is") {
            return Err(self.err("a proposition is `input is [not] term`"));
        }
        self.pos += 2;
        let negated = self.peek() == Some("not");
        if negated {
            self.pos += 1;
        }
        let term = self.peek().ok_or_else(|| self.err("missing term"))?;
        self.pos += 1;
        let input = self
            .inputs
            .iter()
            .position(|v| v.name == name)
            .ok_or_else(|| unknown(self.rule, "input", name))?;
        let term = self.inputs[input]
            .terms
            .iter()
            .position(|t| t.name == term)
            .ok_or_else(|| unknown(self.rule, "term", term))?;
        Ok(Expr::Is {
            input,
            term,
            negated,
        })
    }
}

/// Writes a rule in fuzzylite's syntax (the inverse of [`parse_rule`]).
pub fn rule_text<T: Real>(
    rule: &Rule<T>,
    inputs: &[InputVariable<T>],
    outputs: &[OutputVariable<T>],
) -> String {
    let mut s = String::from("if ");
    write_expr(&mut s, &rule.antecedent, inputs, true);
    s.push_str(" then ");
    for (i, c) in rule.consequents.iter().enumerate() {
        if i > 0 {
            s.push_str(" and ");
        }
        let o = &outputs[c.output];
        let not = if c.negated { "not " } else { "" };
        let _ = write!(s, "{} is {}{}", o.name, not, o.terms[c.term].name);
    }
    if rule.weight != T::one() {
        let _ = write!(s, " with {}", rule.weight);
    }
    s
}

fn write_expr<T>(s: &mut String, e: &Expr, inputs: &[InputVariable<T>], top: bool) {
    match e {
        Expr::Is {
            input,
            term,
            negated,
        } => {
            let v = &inputs[*input];
            let not = if *negated { "not " } else { "" };
            let _ = write!(s, "{} is {}{}", v.name, not, v.terms[*term].name);
        }
        Expr::And(a, b) | Expr::Or(a, b) => {
            // Parenthesise every nested operation: unambiguous whatever the reader's precedence.
            if !top {
                s.push('(');
            }
            write_expr(s, a, inputs, false);
            s.push_str(if matches!(e, Expr::And(..)) {
                " and "
            } else {
                " or "
            });
            write_expr(s, b, inputs, false);
            if !top {
                s.push(')');
            }
        }
    }
}
