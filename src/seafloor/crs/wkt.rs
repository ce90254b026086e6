//! WKT, as `.prj` sidecars hold it: a small parser (OGC and ESRI WKT 1, WKT 2), the CRS a
//! sidecar describes, and the WKT shoal writes for the CRSs it knows (see [`super`]).

use super::super::load::Crs;

/// A WKT node: `KEYWORD[item, item, …]`.
#[derive(Debug, Clone, PartialEq)]
struct Node {
    keyword: String,
    items: Vec<Item>,
}

#[derive(Debug, Clone, PartialEq)]
enum Item {
    /// A quoted string.
    Text(String),
    /// A number or a bare word (e.g. `EAST`).
    Bare(String),
    Node(Node),
}

impl Node {
    fn name(&self) -> &str {
        match self.items.first() {
            Some(Item::Text(t)) => t,
            _ => "",
        }
    }

    fn children<'a>(&'a self, keywords: &'a [&'a str]) -> impl Iterator<Item = &'a Node> + 'a {
        self.items.iter().filter_map(move |i| match i {
            Item::Node(n) if keywords.iter().any(|k| n.keyword.eq_ignore_ascii_case(k)) => Some(n),
            _ => None,
        })
    }

    /// The EPSG code of `AUTHORITY["EPSG", "code"]` or `ID["EPSG", code]` directly below.
    fn epsg(&self) -> Option<u32> {
        self.children(&["AUTHORITY", "ID"]).find_map(|a| {
            let text = |i: Option<&Item>| match i {
                Some(Item::Text(t) | Item::Bare(t)) => Some(t.trim().to_string()),
                _ => None,
            };
            let authority = text(a.items.first())?;
            authority
                .eq_ignore_ascii_case("EPSG")
                .then(|| text(a.items.get(1))?.parse().ok())?
        })
    }

    /// The conversion factors (to metres or radians) of the units below: the node's own
    /// `UNIT`/`LENGTHUNIT`/`ANGLEUNIT`, and those of its `CS` axes (WKT2).
    fn unit_factors(&self, keywords: &[&str]) -> Vec<(String, f64)> {
        let mut out = Vec::new();
        let mut visit = |n: &Node| {
            for u in n.children(keywords) {
                if let Some(Item::Bare(f)) = u.items.get(1) {
                    out.push((u.name().to_string(), f.parse().unwrap_or(f64::NAN)));
                }
            }
        };
        visit(self);
        for axis in self.children(&["AXIS"]) {
            visit(axis);
        }
        out
    }
}

/// Parses WKT text into its outer node.
fn parse_wkt(text: &str) -> Result<Node, String> {
    let chars: Vec<char> = text.trim_start_matches('\u{feff}').chars().collect();
    let mut pos = 0;
    let node = parse_node(&chars, &mut pos, 0)?;
    skip_ws(&chars, &mut pos);
    if pos < chars.len() {
        return Err(format!(
            "unexpected text after the WKT at character {}",
            pos + 1
        ));
    }
    Ok(node)
}

fn skip_ws(c: &[char], pos: &mut usize) {
    while *pos < c.len() && c[*pos].is_whitespace() {
        *pos += 1;
    }
}

fn parse_node(c: &[char], pos: &mut usize, depth: usize) -> Result<Node, String> {
    if depth > 64 {
        return Err("WKT nested more than 64 levels deep".into());
    }
    skip_ws(c, pos);
    let start = *pos;
    while *pos < c.len() && (c[*pos].is_ascii_alphanumeric() || c[*pos] == '_') {
        *pos += 1;
    }
    let keyword: String = c[start..*pos].iter().collect();
    skip_ws(c, pos);
    let close = match c.get(*pos) {
        Some('[') => ']',
        Some('(') => ')',
        _ if keyword.is_empty() => {
            return Err(format!(
                "expected WKT (e.g. GEOGCS[\"WGS 84\", …]) at character {}",
                start + 1
            ))
        }
        _ => {
            return Err(format!(
                "expected [ after {keyword} at character {}",
                *pos + 1
            ))
        }
    };
    *pos += 1;
    let mut items = Vec::new();
    loop {
        skip_ws(c, pos);
        match c.get(*pos) {
            None => return Err(format!("{keyword}[…] is not closed")),
            Some(&ch) if ch == close && items.is_empty() => {
                *pos += 1;
                break;
            }
            Some('"') => {
                *pos += 1;
                let mut s = String::new();
                loop {
                    match c.get(*pos) {
                        None => return Err("a quoted string is not closed".into()),
                        Some('"') if c.get(*pos + 1) == Some(&'"') => {
                            s.push('"');
                            *pos += 2;
                        }
                        Some('"') => {
                            *pos += 1;
                            break;
                        }
                        Some(&ch) => {
                            s.push(ch);
                            *pos += 1;
                        }
                    }
                }
                items.push(Item::Text(s));
            }
            Some(_) => {
                let s = *pos;
                while *pos < c.len() && !matches!(c[*pos], ',' | '[' | ']' | '(' | ')' | '"') {
                    *pos += 1;
                }
                let word: String = c[s..*pos].iter().collect::<String>().trim().to_string();
                if matches!(c.get(*pos), Some('[' | '(')) {
                    *pos = s;
                    items.push(Item::Node(parse_node(c, pos, depth + 1)?));
                } else if word.is_empty() {
                    return Err(format!("empty value in {keyword}[…]"));
                } else {
                    items.push(Item::Bare(word));
                }
            }
        }
        skip_ws(c, pos);
        match c.get(*pos) {
            Some(',') => *pos += 1,
            Some(&ch) if ch == close => {
                *pos += 1;
                break;
            }
            None => return Err(format!("{keyword}[…] is not closed")),
            _ => return Err(format!("expected , or {close} in {keyword}[…]")),
        }
    }
    Ok(Node { keyword, items })
}

/// Lower case, `_` as spaces, runs of spaces collapsed.
fn normalise(s: &str) -> String {
    s.to_lowercase()
        .replace('_', " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

fn is_wgs84(s: &str) -> bool {
    let n = normalise(s).replace(' ', "");
    n.contains("wgs84") || n.contains("wgs1984") || n.contains("worldgeodeticsystem1984")
}

/// "… UTM zone 56S", "…_UTM_Zone_56S", "UTM Zone 56, Southern Hemisphere": (zone, south).
fn utm_zone(name: &str) -> Option<(u16, bool)> {
    let n = normalise(name);
    let rest = &n[n.find("utm zone")? + "utm zone".len()..];
    let rest = rest.trim_start();
    let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
    let zone: u16 = digits.parse().ok().filter(|z| (1..=60).contains(z))?;
    let after = rest[digits.len()..].trim_start_matches([',', ' ']);
    let south = match after.chars().next() {
        Some('s') => true,
        Some('n') => false,
        _ => return None,
    };
    Some((zone, south))
}

/// The CRS a `.prj` sidecar's WKT describes (see the module docs).
pub(crate) fn crs_of_wkt(text: &str) -> Result<Crs, String> {
    let mut top = parse_wkt(text)?;
    let kw = |n: &Node| n.keyword.to_ascii_uppercase();
    if matches!(kw(&top).as_str(), "COMPD_CS" | "COMPOUNDCRS") {
        top = top
            .items
            .iter()
            .find_map(|i| match i {
                Item::Node(n) => Some(n.clone()),
                _ => None,
            })
            .ok_or("a compound CRS without a horizontal CRS")?;
    }
    let code = top.epsg().and_then(|c| u16::try_from(c).ok());
    match kw(&top).as_str() {
        "GEOGCS" | "GEOGCRS" | "GEODCRS" | "GEOGRAPHICCRS" => {
            for (unit, f) in top.unit_factors(&["UNIT", "ANGLEUNIT"]) {
                let degree = std::f64::consts::PI / 180.0;
                if f.is_nan() || (f - degree).abs() > 1e-9 * degree {
                    return Err(format!(
                        "{} is in {unit:?} ({f} rad): only degrees are supported",
                        top.name()
                    ));
                }
            }
            let datum = top
                .children(&["DATUM", "TRF", "GEODETICDATUM"])
                .map(|d| d.name().to_string())
                .collect::<String>();
            let epsg = code.or((is_wgs84(top.name()) || is_wgs84(&datum)).then_some(4326));
            Ok(Crs::Geographic { epsg })
        }
        "PROJCS" | "PROJCRS" | "PROJECTEDCRS" => {
            for (unit, f) in top.unit_factors(&["UNIT", "LENGTHUNIT"]) {
                if f.is_nan() || (f - 1.0).abs() > 1e-9 {
                    return Err(format!(
                        "{} is in {unit:?} ({f} m): only metres are supported",
                        top.name()
                    ));
                }
            }
            let base = top
                .children(&["GEOGCS", "BASEGEOGCRS", "BASEGEODCRS"])
                .flat_map(|g| {
                    std::iter::once(g.name().to_string())
                        .chain(g.children(&["DATUM"]).map(|d| d.name().to_string()))
                })
                .collect::<Vec<_>>()
                .join(" ");
            let wgs84 = is_wgs84(top.name()) || is_wgs84(&base);
            let utm = wgs84
                .then(|| utm_zone(top.name()))
                .flatten()
                .map(|(z, south)| if south { 32700 + z } else { 32600 + z });
            let epsg = code.or(utm);
            Ok(Crs::Projected {
                epsg,
                citation: epsg.is_none().then(|| top.name().to_string()),
            })
        }
        other => Err(format!(
            "the WKT describes a {other}: expected a geographic (GEOGCS) or projected (PROJCS) \
             CRS"
        )),
    }
}

/// ESRI WKT for a `.prj` sidecar of `crs`, when shoal knows it: WGS 84 (EPSG:4326) and the WGS
/// 84 UTM zones (EPSG:326zz/327zz).
pub fn wkt_of(crs: &Crs) -> Option<String> {
    const GEOGCS: &str = "GEOGCS[\"GCS_WGS_1984\",DATUM[\"D_WGS_1984\",SPHEROID[\"WGS_1984\",\
                          6378137.0,298.257223563]],PRIMEM[\"Greenwich\",0.0],\
                          UNIT[\"Degree\",0.0174532925199433]]";
    match crs {
        Crs::Geographic { epsg: Some(4326) } => Some(GEOGCS.to_string()),
        Crs::Projected {
            epsg: Some(c @ (32601..=32660 | 32701..=32760)),
            ..
        } => {
            let (zone, south) = (c % 100, *c > 32700);
            Some(format!(
                "PROJCS[\"WGS_1984_UTM_Zone_{zone}{}\",{GEOGCS},\
                 PROJECTION[\"Transverse_Mercator\"],PARAMETER[\"False_Easting\",500000.0],\
                 PARAMETER[\"False_Northing\",{}],PARAMETER[\"Central_Meridian\",{}],\
                 PARAMETER[\"Scale_Factor\",0.9996],PARAMETER[\"Latitude_Of_Origin\",0.0],\
                 UNIT[\"Meter\",1.0]]",
                if south { "S" } else { "N" },
                if south { "10000000.0" } else { "0.0" },
                -183 + 6 * i32::from(zone)
            ))
        }
        _ => None,
    }
}
