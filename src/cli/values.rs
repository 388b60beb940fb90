//! Parsers for option values, so bad input is refused by name before anything runs.

/// A `WxH` pair of positive whole numbers (grid sizes).
pub fn parse_size(s: &str) -> Result<(u64, u64), String> {
    let (w, h) = split_pair(s, 'x').ok_or_else(|| format!("'{s}' is not WxH, e.g. 9x9"))?;
    let whole = |v: &str| {
        v.trim()
            .parse::<u64>()
            .map_err(|_| format!("'{s}' is not WxH with whole numbers, e.g. 9x9"))
    };
    Ok((whole(w)?, whole(h)?))
}

/// A positive, finite length in metres.
pub fn parse_metres(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number of metres"))?;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(format!(
            "'{s}': a length must be a positive, finite number of metres"
        ))
    }
}

/// A finite number (coordinates, heights, angles).
pub fn parse_finite(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("'{s}' is not a finite number"))
    }
}

/// A number meant as a share from 0 to 1 (braiding). Only the syntax is checked here
/// (negative and large values included): the range is checked with every other range
/// against the layout limits, so the message names the option and the range.
pub fn parse_share(s: &str) -> Result<f64, String> {
    s.trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number from 0 to 1"))
}

/// A percentage from 0 to 100.
pub fn parse_percent(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .trim_end_matches('%')
        .parse()
        .map_err(|_| format!("'{s}' is not a percentage from 0 to 100"))?;
    if (0.0..=100.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("'{s}' is not a percentage from 0 to 100"))
    }
}

/// A point `x,y` of finite numbers.
pub fn parse_point(s: &str) -> Result<[f64; 2], String> {
    let (x, y) = split_pair(s, ',').ok_or_else(|| format!("'{s}' is not x,y, e.g. -4,-4"))?;
    Ok([parse_finite(x)?, parse_finite(y)?])
}

/// A floor size `XxY` in metres.
pub fn parse_floor(s: &str) -> Result<[f64; 2], String> {
    let (x, y) =
        split_pair(s, 'x').ok_or_else(|| format!("'{s}' is not XxY metres, e.g. 10x10"))?;
    Ok([parse_metres(x)?, parse_metres(y)?])
}

fn split_pair(s: &str, separator: char) -> Option<(&str, &str)> {
    s.split_once(separator)
        .or_else(|| s.split_once(separator.to_ascii_uppercase()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_lengths() {
        assert_eq!(parse_size("9x9"), Ok((9, 9)));
        assert_eq!(parse_size("20X15"), Ok((20, 15)));
        assert!(parse_size("9").is_err());
        assert!(parse_size("-1x3").is_err());
        assert!(parse_size("axb").is_err());
        assert_eq!(parse_metres("0.6"), Ok(0.6));
        for bad in ["0", "-1", "NaN", "inf", "x"] {
            assert!(parse_metres(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_point("-4,-4.5"), Ok([-4.0, -4.5]));
        assert!(parse_point("1,NaN").is_err());
        assert_eq!(parse_floor("10x20"), Ok([10.0, 20.0]));
        assert_eq!(parse_share("0.25"), Ok(0.25));
        assert_eq!(parse_share("-0.5"), Ok(-0.5)); // refused later, by range
        for bad in ["half", "", "0,5"] {
            assert!(parse_share(bad).is_err(), "{bad}");
        }
    }
}
