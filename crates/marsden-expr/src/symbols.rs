//! The symbol table: which names an expression may use and what they stand for.

use std::collections::BTreeMap;

use crate::error::SymbolError;
use crate::functions::is_reserved;
use crate::lexer::{is_ident_continue, is_ident_start};

/// What a name stands for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Symbol {
    /// A value supplied at evaluation time: `inputs[slot]`.
    Input(usize),
    /// A value known at compile time (a parameter such as `m` or `g`); folded into the program.
    Constant(f64),
}

/// The names an expression may use, each bound to an input slot or a constant.
///
/// Built-in names (`pi` and the function names) are reserved and cannot be declared.
///
/// ```
/// use marsden_expr::{Symbol, Symbols};
/// let mut symbols = Symbols::with_inputs(["theta", "theta_dot"]).unwrap();
/// symbols.add_constant("g", 9.81).unwrap();
/// assert_eq!(symbols.get("theta_dot"), Some(Symbol::Input(1)));
/// assert_eq!(symbols.input_count(), 2);
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Symbols {
    map: BTreeMap<String, Symbol>,
}

impl Symbols {
    /// An empty table.
    pub fn new() -> Self {
        Self::default()
    }

    /// A table whose inputs are `names`, bound to slots `0, 1, 2, …` in order.
    pub fn with_inputs<I>(names: I) -> Result<Self, SymbolError>
    where
        I: IntoIterator,
        I::Item: AsRef<str>,
    {
        let mut symbols = Self::new();
        for (slot, name) in names.into_iter().enumerate() {
            symbols.add_input(name.as_ref(), slot)?;
        }
        Ok(symbols)
    }

    /// Declare `name` as `symbol`.
    ///
    /// Fails if the name is not an identifier, is reserved, is already declared, or is a
    /// constant with a NaN or infinite value.
    pub fn insert(&mut self, name: &str, symbol: Symbol) -> Result<&mut Self, SymbolError> {
        if !is_identifier(name) {
            return Err(SymbolError::Invalid(name.to_owned()));
        }
        if is_reserved(name) {
            return Err(SymbolError::Reserved(name.to_owned()));
        }
        if self.map.contains_key(name) {
            return Err(SymbolError::Duplicate(name.to_owned()));
        }
        if let Symbol::Constant(value) = symbol
            && !value.is_finite()
        {
            return Err(SymbolError::NonFinite {
                name: name.to_owned(),
                value,
            });
        }
        self.map.insert(name.to_owned(), symbol);
        Ok(self)
    }

    /// Declare `name` as the input in `slot`.
    pub fn add_input(&mut self, name: &str, slot: usize) -> Result<&mut Self, SymbolError> {
        self.insert(name, Symbol::Input(slot))
    }

    /// Declare `name` as a constant (a parameter) with `value`.
    pub fn add_constant(&mut self, name: &str, value: f64) -> Result<&mut Self, SymbolError> {
        self.insert(name, Symbol::Constant(value))
    }

    /// What `name` stands for, if it is declared.
    pub fn get(&self, name: &str) -> Option<Symbol> {
        self.map.get(name).copied()
    }

    /// All declared names, sorted.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.map.keys().map(String::as_str)
    }

    /// All declared names with their meaning, sorted by name.
    pub fn iter(&self) -> impl Iterator<Item = (&str, Symbol)> {
        self.map
            .iter()
            .map(|(name, symbol)| (name.as_str(), *symbol))
    }

    /// Number of declared names.
    pub fn len(&self) -> usize {
        self.map.len()
    }

    /// Whether no names are declared.
    pub fn is_empty(&self) -> bool {
        self.map.is_empty()
    }

    /// One more than the largest declared input slot (0 if there are no inputs): the length of
    /// the inputs slice that fits every expression compiled against this table.
    pub fn input_count(&self) -> usize {
        self.map
            .values()
            .filter_map(|s| match s {
                Symbol::Input(slot) => Some(slot + 1),
                Symbol::Constant(_) => None,
            })
            .max()
            .unwrap_or(0)
    }
}

/// Whether `name` is an identifier of the expression language.
pub fn is_identifier(name: &str) -> bool {
    let mut chars = name.chars();
    chars.next().is_some_and(is_ident_start) && chars.all(is_ident_continue)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn declaring_names() {
        let mut s = Symbols::with_inputs(["x", "y"]).unwrap();
        s.add_constant("m", 2.0).unwrap().add_input("t", 5).unwrap();
        assert_eq!(s.get("m"), Some(Symbol::Constant(2.0)));
        assert_eq!(s.get("z"), None);
        assert_eq!(s.input_count(), 6);
        assert_eq!(s.names().collect::<Vec<_>>(), ["m", "t", "x", "y"]);
        assert_eq!(s.len(), 4);
    }

    #[test]
    fn rejected_names() {
        let mut s = Symbols::with_inputs(["x"]).unwrap();
        assert_eq!(
            s.add_input("x", 1).unwrap_err(),
            SymbolError::Duplicate("x".into())
        );
        assert_eq!(
            s.add_constant("pi", 3.0).unwrap_err(),
            SymbolError::Reserved("pi".into())
        );
        assert_eq!(
            s.add_input("sin", 1).unwrap_err(),
            SymbolError::Reserved("sin".into())
        );
        assert_eq!(
            s.add_input("2x", 1).unwrap_err(),
            SymbolError::Invalid("2x".into())
        );
        assert_eq!(
            s.add_input("", 1).unwrap_err(),
            SymbolError::Invalid(String::new())
        );
        assert!(matches!(
            s.add_constant("g", f64::NAN),
            Err(SymbolError::NonFinite { .. })
        ));
    }
}
