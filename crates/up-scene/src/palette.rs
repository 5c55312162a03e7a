//! The named balloon colours: the one table every part of UP reads (scene
//! checks, the OBJ/MTL export, the web app through the wasm module).

/// A colour a scene may name.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PaletteColor {
    /// Lower-case name, as written in scenes and in `balloon_<name>.mtl`.
    pub name: &'static str,
    /// sRGB in 0..1, as party latex looks: saturated, not pure primaries.
    pub rgb: [f32; 3],
}

/// Every named colour, in palette order; the first `DEFAULT_COLOR_COUNT` are
/// the original scene's.
pub const PALETTE: &[PaletteColor] = &[
    PaletteColor {
        name: "red",
        rgb: [0.80, 0.06, 0.08],
    },
    PaletteColor {
        name: "yellow",
        rgb: [0.98, 0.80, 0.10],
    },
    PaletteColor {
        name: "blue",
        rgb: [0.08, 0.30, 0.85],
    },
    PaletteColor {
        name: "green",
        rgb: [0.10, 0.62, 0.22],
    },
    PaletteColor {
        name: "purple",
        rgb: [0.45, 0.15, 0.65],
    },
    PaletteColor {
        name: "orange",
        rgb: [0.98, 0.45, 0.06],
    },
    PaletteColor {
        name: "pink",
        rgb: [0.96, 0.45, 0.65],
    },
    PaletteColor {
        name: "white",
        rgb: [0.93, 0.93, 0.92],
    },
];

/// How many of the palette's first colours the original scene uses.
pub const DEFAULT_COLOR_COUNT: usize = 6;

/// The RGB of a named colour (case-insensitive).
pub fn color_rgb(name: &str) -> Option<[f32; 3]> {
    PALETTE
        .iter()
        .find(|c| c.name.eq_ignore_ascii_case(name))
        .map(|c| c.rgb)
}

/// The names, in palette order.
pub fn color_names() -> impl ExactSizeIterator<Item = &'static str> {
    PALETTE.iter().map(|c| c.name)
}

/// `"#rrggbb"` → RGB in 0–1 (sRGB, as written); colour names are looked up in the `palette`.
pub fn parse_color(name: &str) -> Option<[f32; 3]> {
    if let Some(hex) = name.strip_prefix('#') {
        if hex.len() != 6 || !hex.is_ascii() {
            return None;
        }
        let channel = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
        return Some([channel(0)?, channel(2)?, channel(4)?].map(|c| f32::from(c) / 255.0));
    }
    color_rgb(name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_lower_case_and_colours_in_range() {
        for (i, c) in PALETTE.iter().enumerate() {
            assert_eq!(c.name, c.name.to_ascii_lowercase());
            assert!(PALETTE[..i].iter().all(|d| d.name != c.name), "{}", c.name);
            assert!(c.rgb.iter().all(|v| (0.0..=1.0).contains(v)), "{c:?}");
            assert_eq!(color_rgb(c.name), Some(c.rgb));
        }
        assert!(DEFAULT_COLOR_COUNT <= PALETTE.len());
        assert_eq!(color_names().len(), PALETTE.len());
    }

    #[test]
    fn lookup_ignores_case_and_refuses_unknown_names() {
        assert_eq!(color_rgb("Red"), color_rgb("red"));
        assert_eq!(color_rgb("WHITE"), Some([0.93, 0.93, 0.92]));
        assert_eq!(color_rgb("chartreuse"), None);
        assert_eq!(color_rgb(""), None);
    }
}
