//! Importer for external implicit expressions in the SSA text format of the Prospero
//! Challenge (`prospero.vm`): one operation per line, `_id opcode args...`, with opcodes
//! `var-x`, `var-y`, `const`, `add`, `sub`, `mul`, `neg`, `square`, `sqrt`, `min` and `max`.
//! Lines starting with `#` and blank lines are ignored; the last operation is the result.
//!
//! The expression becomes a level graph, so it can be a terrain like any level: arithmetic
//! maps to the expression nodes of [`Node`], `min`/`max` to `Union`/`Intersection`, values
//! used more than once become named nodes (`Ref`), and left-nested chains of the same
//! `min`/`max` whose inner value has no other use are flattened into one n-ary node. A
//! left fold is exactly the nested binary operation (`min(min(a, b), c)` is `Union[a, b,
//! c]`), so flattening changes no bit; it keeps the graph shallow (prospero's 676 levels
//! become 11).

use std::collections::BTreeMap;

use thiserror::Error;

use super::error::LevelError;
use super::graph::{Graph, GraphLimits};
use super::node::Node;

/// Largest accepted input, bytes.
pub const MAX_VM_BYTES: usize = 16 * 1024 * 1024;
/// Most operations an expression may have.
pub const MAX_VM_OPS: usize = 200_000;

/// Why an expression could not be imported. Messages name the line.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum ImportError {
    /// The input is larger than [`MAX_VM_BYTES`].
    #[error("expression is {size} bytes, over the limit of {limit} bytes")]
    TooLarge {
        /// Input size.
        size: usize,
        /// The limit.
        limit: usize,
    },
    /// The input has more than [`MAX_VM_OPS`] operations.
    #[error("line {line}: more than {limit} operations")]
    TooManyOps {
        /// 1-based line number.
        line: usize,
        /// The limit.
        limit: usize,
    },
    /// A line is malformed.
    #[error("line {line}: {reason}")]
    Syntax {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// There is no operation at all.
    #[error("the expression has no operations")]
    Empty,
    /// The graph built from the expression was rejected.
    #[error("the imported graph is invalid: {0}")]
    Graph(#[from] LevelError),
}

/// An imported expression: its root node and the named nodes it refers to.
#[derive(Clone, Debug, PartialEq)]
pub struct Expression {
    /// The result of the last operation.
    pub root: Node,
    /// Values used more than once, by name (`Ref(name)` in `root` and in each other).
    pub nodes: BTreeMap<String, Node>,
    /// Number of operations read.
    pub ops: usize,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Code {
    X,
    Y,
    Const,
    Add,
    Sub,
    Mul,
    Neg,
    Square,
    Sqrt,
    Min,
    Max,
}

impl Code {
    fn parse(s: &str) -> Option<(Code, usize)> {
        Some(match s {
            "var-x" => (Code::X, 0),
            "var-y" => (Code::Y, 0),
            "const" => (Code::Const, 1),
            "add" => (Code::Add, 2),
            "sub" => (Code::Sub, 2),
            "mul" => (Code::Mul, 2),
            "neg" => (Code::Neg, 1),
            "square" => (Code::Square, 1),
            "sqrt" => (Code::Sqrt, 1),
            "min" => (Code::Min, 2),
            "max" => (Code::Max, 2),
            _ => return None,
        })
    }
}

/// One parsed line: opcode, operand indices (or the constant).
#[derive(Clone, Copy, Debug)]
struct Line {
    code: Code,
    args: [usize; 2],
    value: f32,
}

/// Parses the text into operations whose operands are indices of earlier operations.
fn parse_lines(text: &str) -> Result<(Vec<Line>, Vec<String>), ImportError> {
    if text.len() > MAX_VM_BYTES {
        return Err(ImportError::TooLarge {
            size: text.len(),
            limit: MAX_VM_BYTES,
        });
    }
    let mut ids: BTreeMap<&str, usize> = BTreeMap::new();
    let mut names = Vec::new();
    let mut lines = Vec::new();
    for (n, raw) in text.lines().enumerate() {
        let line_no = n + 1;
        let raw = raw.trim();
        if raw.is_empty() || raw.starts_with('#') {
            continue;
        }
        if lines.len() >= MAX_VM_OPS {
            return Err(ImportError::TooManyOps {
                line: line_no,
                limit: MAX_VM_OPS,
            });
        }
        let syntax = |reason: String| ImportError::Syntax {
            line: line_no,
            reason,
        };
        let mut words = raw.split_whitespace();
        let (Some(id), Some(op)) = (words.next(), words.next()) else {
            return Err(syntax(format!("expected `id opcode args`, got `{raw}`")));
        };
        let (code, arity) =
            Code::parse(op).ok_or_else(|| syntax(format!("unknown opcode `{op}`")))?;
        let args: Vec<&str> = words.collect();
        if args.len() != arity {
            return Err(syntax(format!(
                "`{op}` takes {arity} operand(s), got {}",
                args.len()
            )));
        }
        let mut line = Line {
            code,
            args: [0; 2],
            value: 0.0,
        };
        if code == Code::Const {
            let v: f32 = args[0]
                .parse()
                .map_err(|_| syntax(format!("`{}` is not a number", args[0])))?;
            if !v.is_finite() {
                return Err(syntax(format!("constant {v} is not finite")));
            }
            line.value = v;
        } else {
            for (slot, a) in line.args.iter_mut().zip(&args) {
                *slot = *ids
                    .get(a)
                    .ok_or_else(|| syntax(format!("operand `{a}` is not defined above")))?;
            }
        }
        if ids.insert(id, lines.len()).is_some() {
            return Err(syntax(format!("`{id}` is defined twice")));
        }
        names.push(id.to_string());
        lines.push(line);
    }
    if lines.is_empty() {
        return Err(ImportError::Empty);
    }
    Ok((lines, names))
}

impl Line {
    fn operands(&self) -> &[usize] {
        match self.code {
            Code::X | Code::Y | Code::Const => &[],
            Code::Neg | Code::Square | Code::Sqrt => &self.args[..1],
            _ => &self.args,
        }
    }
}

/// Builds the node of operation `i`; `shared` values are referenced by name.
struct Builder<'a> {
    lines: &'a [Line],
    names: &'a [String],
    uses: Vec<u32>,
}

impl Builder<'_> {
    /// The operand `i` as a child: a reference when the value is shared.
    fn operand(&self, i: usize) -> Node {
        let l = &self.lines[i];
        let leaf = matches!(l.code, Code::X | Code::Y | Code::Const);
        if self.uses[i] > 1 && !leaf {
            Node::Ref(self.names[i].clone())
        } else {
            self.node(i)
        }
    }

    /// The children of a flattened left-nested `min`/`max` chain ending at `i`.
    fn chain(&self, i: usize) -> Vec<Node> {
        let code = self.lines[i].code;
        let mut rights = Vec::new();
        let mut at = i;
        loop {
            let l = &self.lines[at];
            rights.push(l.args[1]);
            let inner = l.args[0];
            if self.lines[inner].code == code && self.uses[inner] == 1 {
                at = inner;
            } else {
                rights.push(inner);
                break;
            }
        }
        rights.iter().rev().map(|&j| self.operand(j)).collect()
    }

    fn node(&self, i: usize) -> Node {
        let l = &self.lines[i];
        let un = |j: usize| Box::new(self.operand(l.args[j]));
        match l.code {
            Code::X => Node::X,
            Code::Y => Node::Y,
            Code::Const => Node::Const(l.value),
            Code::Add => Node::Add(un(0), un(1)),
            Code::Sub => Node::Sub(un(0), un(1)),
            Code::Mul => Node::Mul(un(0), un(1)),
            Code::Neg => Node::Neg(un(0)),
            Code::Square => Node::Square(un(0)),
            Code::Sqrt => Node::Sqrt(un(0)),
            Code::Min => Node::Union(self.chain(i)),
            Code::Max => Node::Intersection(self.chain(i)),
        }
    }
}

impl Expression {
    /// Parses the SSA text.
    pub fn parse(text: &str) -> Result<Expression, ImportError> {
        let (lines, names) = parse_lines(text)?;
        let mut uses = vec![0u32; lines.len()];
        for l in &lines {
            for &a in l.operands() {
                uses[a] = uses[a].saturating_add(1);
            }
        }
        let b = Builder {
            lines: &lines,
            names: &names,
            uses,
        };
        let last = lines.len() - 1;
        // Build the shared nodes that are reachable from the result (every shared value
        // is, except dead code, which is dropped).
        let index: BTreeMap<&str, usize> = names
            .iter()
            .enumerate()
            .map(|(i, n)| (n.as_str(), i))
            .collect();
        let mut refs = Refs {
            index,
            seen: vec![false; lines.len()],
            stack: Vec::new(),
        };
        let mut nodes = BTreeMap::new();
        let root = b.node(last);
        refs.collect(&root);
        while let Some(i) = refs.stack.pop() {
            let n = b.node(i);
            refs.collect(&n);
            nodes.insert(names[i].clone(), n);
        }
        Ok(Expression {
            root,
            nodes,
            ops: lines.len(),
        })
    }

    /// Compiles the expression into a graph. The limits allow expressions of up to
    /// [`MAX_VM_OPS`] operations (the evaluation-cost limit is the default's).
    pub fn graph(&self) -> Result<Graph, ImportError> {
        let limits = GraphLimits {
            max_nodes: MAX_VM_OPS + 1,
            ..GraphLimits::default()
        };
        Ok(Graph::compile_with_limits(&self.root, &self.nodes, limits)?)
    }
}

/// The shared values still to build.
struct Refs<'a> {
    index: BTreeMap<&'a str, usize>,
    seen: Vec<bool>,
    stack: Vec<usize>,
}

impl Refs<'_> {
    /// Queues every not yet seen `Ref` under `node`.
    fn collect(&mut self, node: &Node) {
        if let Node::Ref(name) = node {
            let unseen = self.index.get(name.as_str()).filter(|&&i| !self.seen[i]);
            if let Some(&i) = unseen {
                self.seen[i] = true;
                self.stack.push(i);
            }
            return;
        }
        for (_, child) in node.children() {
            self.collect(child);
        }
    }
}

/// Parses the SSA text and compiles it into a graph.
pub fn graph_from_vm(text: &str) -> Result<Graph, ImportError> {
    Expression::parse(text)?.graph()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Sdf;
    use glam::Vec2;

    #[test]
    fn imports_and_evaluates_a_circle() {
        let text = "# unit circle\n_0 var-x\n_1 var-y\n_2 square _0\n_3 square _1\n_4 add _2 _3\n_5 sqrt _4\n_6 const 1\n_7 sub _5 _6\n";
        let g = graph_from_vm(text).unwrap();
        assert_eq!(g.distance(Vec2::new(3.0, 4.0)), 4.0);
        assert_eq!(g.distance(Vec2::ZERO), -1.0);
        assert!((g.lipschitz() - std::f32::consts::SQRT_2).abs() < 1e-3);
    }

    #[test]
    fn flattens_min_chains_and_shares_values() {
        let text = "_0 var-x\n_1 const 1\n_2 sub _0 _1\n_3 const 2\n_4 sub _0 _3\n_5 min _2 _4\n_6 neg _2\n_7 min _5 _6\n";
        let e = Expression::parse(text).unwrap();
        let Node::Union(children) = &e.root else {
            panic!("expected a union, got {:?}", e.root)
        };
        assert_eq!(children.len(), 3);
        assert_eq!(e.nodes.len(), 1, "{:?}", e.nodes);
        let g = e.graph().unwrap();
        // min(x-1, x-2, -(x-1)) at x = 5: min(4, 3, -4).
        assert_eq!(g.distance(Vec2::new(5.0, 0.0)), -4.0);
    }

    #[test]
    fn errors_name_the_line() {
        let cases = [
            ("_0 var-x\n_1 frob _0\n", "line 2: unknown opcode `frob`"),
            (
                "_0 var-x\n_1 add _0\n",
                "line 2: `add` takes 2 operand(s), got 1",
            ),
            (
                "_0 var-x\n_1 add _0 _9\n",
                "line 2: operand `_9` is not defined above",
            ),
            ("_0 const abc\n", "line 1: `abc` is not a number"),
            ("_0 const inf\n", "line 1: constant inf is not finite"),
            ("_0 var-x\n_0 var-y\n", "line 2: `_0` is defined twice"),
            ("# nothing\n", "the expression has no operations"),
            ("_0\n", "line 1: expected `id opcode args`, got `_0`"),
        ];
        for (text, want) in cases {
            let got = Expression::parse(text).unwrap_err().to_string();
            assert_eq!(got, want, "for {text:?}");
        }
    }
}
