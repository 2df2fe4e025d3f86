//! What an instance says, and to whom: the statuses both standards share, the log categories,
//! and the sink each standard's boundary gives an instance (its logger callback).

/// A call's outcome, as FMI 2.0 and FMI 3.0 both number it: FMI 3.0's fmi3Status itself (FMI
/// 2.0's adds fmi2Pending, which never occurs here: steps are synchronous).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Status {
    Ok = 0,
    Warning = 1,
    Discard = 2,
    Error = 3,
    Fatal = 4,
}

pub const CATEGORY_ERROR: &str = "logStatusError";
pub const CATEGORY_WARNING: &str = "logStatusWarning";
pub const CATEGORY_CALLS: &str = "logCalls";

/// Where an instance's messages go: the importer's logger, through its standard's callback.
pub trait LogSink {
    fn log(&self, status: Status, category: &str, message: &str);
}

/// The message with every number that Rust's `{}` spells out in more than 21 characters (1e300
/// as 301 digits, 1e-300 as 300 zeros and a 1) in scientific notation instead.
pub fn readable_numbers(message: &str) -> String {
    const LONGEST: usize = 21;
    let mut out = String::with_capacity(message.len());
    let mut run = String::new();
    let flush = |run: &mut String, out: &mut String| {
        // A run can end on a sentence's full stop: keep it out of the number.
        let number = run.strip_suffix('.').unwrap_or(run);
        match number.parse::<f64>() {
            Ok(x) if number.len() > LONGEST => {
                out.push_str(&format!("{x:e}"));
                out.push_str(&run[number.len()..]);
            }
            _ => out.push_str(run),
        }
        run.clear();
    };
    for ch in message.chars() {
        if ch.is_ascii_digit() || ch == '.' {
            run.push(ch);
        } else {
            flush(&mut run, &mut out);
            out.push(ch);
        }
    }
    flush(&mut run, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::readable_numbers;

    #[test]
    fn long_numbers_become_scientific_and_the_rest_stays() {
        let huge = format!("h = {} s.", 1e300);
        assert_eq!(readable_numbers(&huge), "h = 1e300 s.");
        let tiny = format!("m = -{} kg: expected", 2.2250738585072014e-308);
        assert_eq!(
            readable_numbers(&tiny),
            "m = -2.2250738585072014e-308 kg: expected"
        );
        let plain = "t = 0.06283185307179587 by 1e-5, v1.2.3, 12345678901234567890 ok";
        assert_eq!(readable_numbers(plain), plain);
    }
}
