//! Helpers shared by the integration tests: the committed reference data and a minimal JSON
//! reader for it (the crate has no JSON dependency).
#![allow(dead_code)]

use std::collections::BTreeMap;

/// A parsed JSON value (numbers are kept as their source text).
#[derive(Debug, Clone)]
pub enum Json {
    Null,
    Bool(bool),
    Number(String),
    Text(String),
    Array(Vec<Json>),
    Object(BTreeMap<String, Json>),
}

impl Json {
    pub fn field(&self, name: &str) -> &Json {
        match self {
            Json::Object(map) => map
                .get(name)
                .unwrap_or_else(|| panic!("reference data lacks field {name:?}")),
            other => panic!("expected an object with field {name:?}, got {other:?}"),
        }
    }

    pub fn array(&self) -> &[Json] {
        match self {
            Json::Array(items) => items,
            other => panic!("expected an array, got {other:?}"),
        }
    }

    /// A number, or a string holding a decimal number, correctly rounded to f64.
    pub fn as_f64(&self) -> f64 {
        let text = match self {
            Json::Number(text) | Json::Text(text) => text,
            other => panic!("expected a number, got {other:?}"),
        };
        text.parse()
            .unwrap_or_else(|_| panic!("not a decimal number: {text:?}"))
    }

    pub fn as_usize(&self) -> usize {
        match self {
            Json::Number(text) => text.parse().expect("an unsigned integer"),
            other => panic!("expected an integer, got {other:?}"),
        }
    }

    pub fn f64_vec(&self) -> Vec<f64> {
        self.array().iter().map(Json::as_f64).collect()
    }
}

/// Parses a JSON document (panics with a position on malformed input: test data only).
pub fn parse_json(text: &str) -> Json {
    let mut parser = Parser {
        bytes: text.as_bytes(),
        position: 0,
    };
    let value = parser.value();
    parser.skip_space();
    assert_eq!(parser.position, parser.bytes.len(), "trailing characters");
    value
}

struct Parser<'a> {
    bytes: &'a [u8],
    position: usize,
}

impl Parser<'_> {
    fn skip_space(&mut self) {
        while self.position < self.bytes.len() && self.bytes[self.position].is_ascii_whitespace() {
            self.position += 1;
        }
    }

    fn peek(&mut self) -> u8 {
        self.skip_space();
        *self
            .bytes
            .get(self.position)
            .unwrap_or_else(|| panic!("unexpected end of JSON"))
    }

    fn expect(&mut self, byte: u8) {
        assert_eq!(self.peek(), byte, "at byte {}", self.position);
        self.position += 1;
    }

    fn value(&mut self) -> Json {
        match self.peek() {
            b'{' => {
                self.position += 1;
                let mut map = BTreeMap::new();
                if self.peek() == b'}' {
                    self.position += 1;
                    return Json::Object(map);
                }
                loop {
                    let key = self.string();
                    self.expect(b':');
                    map.insert(key, self.value());
                    match self.peek() {
                        b',' => self.position += 1,
                        b'}' => {
                            self.position += 1;
                            return Json::Object(map);
                        }
                        other => panic!("unexpected {:?} at {}", other as char, self.position),
                    }
                }
            }
            b'[' => {
                self.position += 1;
                let mut items = Vec::new();
                if self.peek() == b']' {
                    self.position += 1;
                    return Json::Array(items);
                }
                loop {
                    items.push(self.value());
                    match self.peek() {
                        b',' => self.position += 1,
                        b']' => {
                            self.position += 1;
                            return Json::Array(items);
                        }
                        other => panic!("unexpected {:?} at {}", other as char, self.position),
                    }
                }
            }
            b'"' => Json::Text(self.string()),
            b't' => self.word("true", Json::Bool(true)),
            b'f' => self.word("false", Json::Bool(false)),
            b'n' => self.word("null", Json::Null),
            _ => {
                let start = self.position;
                while self.position < self.bytes.len()
                    && matches!(
                        self.bytes[self.position],
                        b'0'..=b'9' | b'-' | b'+' | b'.' | b'e' | b'E'
                    )
                {
                    self.position += 1;
                }
                assert!(self.position > start, "no value at byte {start}");
                Json::Number(
                    String::from_utf8_lossy(&self.bytes[start..self.position]).into_owned(),
                )
            }
        }
    }

    fn word(&mut self, word: &str, value: Json) -> Json {
        assert!(self.bytes[self.position..].starts_with(word.as_bytes()));
        self.position += word.len();
        value
    }

    fn string(&mut self) -> String {
        self.expect(b'"');
        let start = self.position;
        while self.bytes[self.position] != b'"' {
            assert_ne!(
                self.bytes[self.position], b'\\',
                "escapes are not supported"
            );
            self.position += 1;
        }
        let text = String::from_utf8_lossy(&self.bytes[start..self.position]).into_owned();
        self.position += 1;
        text
    }
}

/// The committed reference file of Gauss–Legendre and Gauss–Kronrod rules.
pub fn gauss_legendre_reference() -> Json {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/reference/gauss_legendre.json"
    );
    let text =
        std::fs::read_to_string(path).unwrap_or_else(|error| panic!("cannot read {path}: {error}"));
    parse_json(&text)
}

/// Distance in units in the last place of `reference`: |computed − reference| / ulp(reference),
/// where ulp(r) is the spacing of doubles at |r| (the smallest subnormal spacing at r = 0).
pub fn ulp_distance(computed: f64, reference: f64) -> f64 {
    let magnitude = reference.abs();
    let ulp = if magnitude == 0.0 {
        f64::from_bits(1)
    } else {
        let next = f64::from_bits(magnitude.to_bits() + 1);
        next - magnitude
    };
    (computed - reference).abs() / ulp
}
