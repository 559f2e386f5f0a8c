//! Numeric option values: a number kept as typed (its messages name what the user wrote) and
//! three coordinates.
#![forbid(unsafe_code)]

/// A number as typed and as parsed: a message about it names what was typed (`1e39`, which is
/// `inf` once parsed).
#[derive(Clone, Debug)]
pub struct TypedF32 {
    pub value: f32,
    pub text: String,
}

impl TypedF32 {
    /// One sentence naming option `--name` and the value as typed when it is not finite, or
    /// outside `within` (`lo`, `hi`, how the sentence says the range).
    pub fn check(&self, name: &str, within: Option<(f32, f32, &str)>) -> Result<(), String> {
        let v = self.value;
        let why = self.in_f32();
        match within {
            _ if v.is_finite() && within.is_none_or(|(lo, hi, _)| (lo..=hi).contains(&v)) => Ok(()),
            Some((.., range)) => Err(format!("--{name} {} is not {range}{why}", self.text)),
            None => Err(format!(
                "--{name} {} is not a finite number{why}",
                self.text
            )),
        }
    }

    /// Why a number typed finite and non-zero reads otherwise in single precision ("" if it
    /// does not): the clause a sentence refusing it adds.
    pub fn in_f32(&self) -> &'static str {
        match self.text.trim().parse::<f64>() {
            Ok(x) if x.is_finite() && self.value.is_infinite() => {
                " in single precision (it is beyond f32's largest, about 3.4e38)"
            }
            Ok(x) if x != 0.0 && self.value == 0.0 => {
                " in single precision (it is below f32's smallest, about 1.4e-45, and reads as 0)"
            }
            _ => "",
        }
    }
}

impl TypedF32 {
    /// Where the number typed lies `inside` a range that its single-precision value does not
    /// (`179.999999` reads as 180), the clause a sentence refusing it adds ("" otherwise).
    pub fn in_f32_range(&self, inside: impl Fn(f64) -> bool) -> String {
        match self.text.trim().parse::<f64>() {
            Ok(x) if inside(x) && !inside(self.value as f64) => {
                format!(" in single precision (it reads as {})", self.value)
            }
            _ => String::new(),
        }
    }
}

impl From<f32> for TypedF32 {
    /// A value given by the program (a default), named as a pixel error is printed.
    fn from(value: f32) -> Self {
        Self {
            value,
            text: meshrefine::lod::px(value),
        }
    }
}

/// [`TypedF32`]: any text `f32` parses, the spaces around it left out as `--eye`'s are (its
/// checks are the option's own, in one sentence).
pub fn typed_f32(s: &str) -> Result<TypedF32, String> {
    let s = s.trim();
    let value = s.parse::<f32>().map_err(|e| format!("{e}"))?;
    Ok(TypedF32 {
        value,
        text: s.to_string(),
    })
}

/// A whole number as typed (`--octaves`; read through [`super::choices::Trimmed`], which
/// leaves out the spaces and names an empty value): any sign and size, so that the command's
/// own range check names a negative or huge count as typed; what is no whole number is the
/// parser's error.
pub fn whole_number(s: &str) -> Result<String, String> {
    let digits = s.strip_prefix(['-', '+']).unwrap_or(s);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        // The value as the parser quotes it is as typed: where a character there shows nothing,
        // say it escaped.
        let shown = meshrefine::paths::printable(s);
        return Err(match shown != s {
            true => format!("not a whole number ('{shown}')"),
            false => "not a whole number".into(),
        });
    }
    Ok(s.to_string())
}

/// A parser of a whole number in `range` (`--level`, `--width`, an item of `--levels`; read
/// through [`super::choices::Trimmed`]): what is no whole number is called so, as
/// [`whole_number`] words it (not the integer parser's "invalid digit found in string"), and one
/// outside the range names it (`2000 is not in 1..=1024`, clap's words).
pub fn whole_in(
    range: std::ops::RangeInclusive<u32>,
) -> impl Fn(&str) -> Result<u32, String> + Clone + Send + Sync + 'static {
    move |s: &str| {
        whole_number(s)?;
        let (lo, hi) = (range.start(), range.end());
        match s.parse::<i128>() {
            Ok(v) if (*lo as i128..=*hi as i128).contains(&v) => Ok(v as u32),
            _ => Err(format!(
                "{} is not in {lo}..={hi}",
                meshrefine::mesh::shown_word(s)
            )),
        }
    }
}

/// A point as typed and as parsed (`--eye`, `--look-at`): a message about it names what was
/// typed.
#[derive(Clone, Debug)]
pub struct TypedVec3 {
    pub value: [f32; 3],
    pub text: String,
}

/// [`TypedVec3`]: [`parse_vec3`], keeping the text.
pub fn typed_vec3(s: &str) -> Result<TypedVec3, String> {
    Ok(TypedVec3 {
        value: parse_vec3(s)?,
        text: s.trim().to_string(),
    })
}

/// `X,Y,Z`: three numbers, any that `f32` parses (`nan`, `inf` and `1e39` included: the
/// camera's check names them in one sentence, [`TypedVec3::check`]); what is not three numbers
/// is the parser's error.
pub fn parse_vec3(s: &str) -> Result<[f32; 3], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let numbers: Vec<f32> = parts.iter().filter_map(|p| p.parse().ok()).collect();
    match numbers[..] {
        [x, y, z] if parts.len() == 3 => Ok([x, y, z]),
        _ => Err(format!("'{s}' is not three numbers X,Y,Z")),
    }
}

impl TypedVec3 {
    /// One sentence naming option `--name` and the point as typed when a coordinate is not
    /// finite; a number finite as typed but beyond single precision says so.
    pub fn check(&self, name: &str) -> Result<(), String> {
        if self.value.iter().all(|v| v.is_finite()) {
            return Ok(());
        }
        let typed_finite =
            (self.text.split(',')).all(|p| p.trim().parse::<f64>().is_ok_and(f64::is_finite));
        let why = if typed_finite {
            " in single precision (one is beyond f32's largest, about 3.4e38)"
        } else {
            ""
        };
        Err(format!(
            "--{name} {} is not three finite numbers X,Y,Z{why}",
            self.text
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::{parse_vec3, typed_f32, typed_vec3};

    /// A number reads without the spaces around it, and keeps its text as typed inside them.
    #[test]
    fn numbers_read_without_surrounding_spaces() {
        let t = typed_f32(" 179.90 ").unwrap();
        assert_eq!((t.value, t.text.as_str()), (179.9, "179.90"));
        assert!(typed_f32(" ").is_err() && typed_f32("1 2").is_err());
    }

    /// Three numbers, else the parser's sentence naming the text; the check then refuses
    /// what is not finite, saying so where a number finite as typed is beyond single precision.
    #[test]
    fn points_are_three_finite_numbers() {
        assert_eq!(parse_vec3(" 1, -2.5,3e2"), Ok([1.0, -2.5, 300.0]));
        for bad in ["1,2", "1,2,3,4", "a,b,c", ""] {
            let e = parse_vec3(bad).unwrap_err();
            assert_eq!(e, format!("'{bad}' is not three numbers X,Y,Z"));
        }
        for bad in ["nan,0,0", "1, inf,0"] {
            let e = typed_vec3(bad).unwrap().check("eye").unwrap_err();
            assert_eq!(e, format!("--eye {bad} is not three finite numbers X,Y,Z"));
        }
        let e = typed_vec3("1e39,0,0")
            .unwrap()
            .check("look-at")
            .unwrap_err();
        assert_eq!(
            e,
            "--look-at 1e39,0,0 is not three finite numbers X,Y,Z in single precision (one is beyond f32's largest, about 3.4e38)"
        );
        assert!(typed_vec3(" 1,2,3 ").unwrap().check("eye").is_ok());
    }
}
