//! Values echoed back in error messages, cut to a readable length.

/// The longest value an error message echoes whole, in characters.
pub const ECHO_MAX_CHARS: usize = 80;

/// `text` as an error message echoes it: whole up to [`ECHO_MAX_CHARS`]
/// characters, else its first ones, an ellipsis and its length (a 10 MB
/// field must not be printed back whole).
///
/// ```
/// assert_eq!(datasets::echo("1.5e3"), "1.5e3");
/// assert!(datasets::echo(&"9".repeat(1000)).ends_with("… (1000 characters)"));
/// ```
pub fn echo(text: &str) -> String {
    let chars = text.chars().count();
    if chars <= ECHO_MAX_CHARS {
        return text.to_string();
    }
    let head: String = text.chars().take(ECHO_MAX_CHARS).collect();
    format!("{head}… ({chars} characters)")
}

#[cfg(test)]
mod tests {
    #[test]
    fn long_values_are_cut_with_their_length() {
        assert_eq!(super::echo("1.5e3"), "1.5e3");
        let long = "9".repeat(10_000_000);
        let echoed = super::echo(&long);
        assert_eq!(echoed, format!("{}… (10000000 characters)", "9".repeat(80)));
    }
}
