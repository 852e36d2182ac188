//! A reader for the subset of JSON the reference files use (objects, arrays, strings without
//! escapes beyond `\\x`, numbers, true, false, null), so the tests need no JSON dependency.

#![allow(dead_code)]

use nalgebra::Vector3;
use std::collections::BTreeMap;

/// A JSON value (the subset the reference files use).
#[derive(Debug, Clone)]
pub enum Json {
    Null,
    Bool,
    Number(f64),
    Text(String),
    List(Vec<Json>),
    Map(BTreeMap<String, Json>),
}

struct Parser<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Parser<'_> {
    fn skip(&mut self) {
        while self.at < self.bytes.len() && self.bytes[self.at].is_ascii_whitespace() {
            self.at += 1;
        }
    }

    fn expect(&mut self, c: u8) {
        self.skip();
        assert_eq!(
            self.bytes[self.at], c,
            "JSON: expected '{}' at byte {}",
            c as char, self.at
        );
        self.at += 1;
    }

    fn value(&mut self) -> Json {
        self.skip();
        match self.bytes[self.at] {
            b'{' => {
                self.at += 1;
                let mut map = BTreeMap::new();
                self.skip();
                if self.bytes[self.at] == b'}' {
                    self.at += 1;
                    return Json::Map(map);
                }
                loop {
                    let Json::Text(key) = self.value() else {
                        panic!("JSON: key")
                    };
                    self.expect(b':');
                    map.insert(key, self.value());
                    self.skip();
                    self.at += 1;
                    if self.bytes[self.at - 1] == b'}' {
                        return Json::Map(map);
                    }
                }
            }
            b'[' => {
                self.at += 1;
                let mut list = vec![];
                self.skip();
                if self.bytes[self.at] == b']' {
                    self.at += 1;
                    return Json::List(list);
                }
                loop {
                    list.push(self.value());
                    self.skip();
                    self.at += 1;
                    if self.bytes[self.at - 1] == b']' {
                        return Json::List(list);
                    }
                }
            }
            b'"' => {
                self.at += 1;
                let mut text = String::new();
                while self.bytes[self.at] != b'"' {
                    if self.bytes[self.at] == b'\\' {
                        self.at += 1;
                    }
                    text.push(self.bytes[self.at] as char);
                    self.at += 1;
                }
                self.at += 1;
                Json::Text(text)
            }
            b't' => {
                self.at += 4;
                Json::Bool
            }
            b'f' => {
                self.at += 5;
                Json::Bool
            }
            b'n' => {
                self.at += 4;
                Json::Null
            }
            _ => {
                let start = self.at;
                while self.at < self.bytes.len()
                    && matches!(
                        self.bytes[self.at],
                        b'0'..=b'9' | b'-' | b'+' | b'.' | b'e' | b'E'
                    )
                {
                    self.at += 1;
                }
                let text = std::str::from_utf8(&self.bytes[start..self.at]).unwrap();
                Json::Number(
                    text.parse()
                        .unwrap_or_else(|_| panic!("JSON number {text}")),
                )
            }
        }
    }
}

impl Json {
    pub fn get(&self, key: &str) -> &Json {
        match self {
            Json::Map(m) => m.get(key).unwrap_or_else(|| panic!("missing key {key}")),
            _ => panic!("not an object"),
        }
    }

    pub fn number(&self) -> f64 {
        match self {
            Json::Number(x) => *x,
            Json::Text(s) => s.parse().unwrap_or_else(|_| panic!("not a decimal: {s}")),
            other => panic!("not a number: {other:?}"),
        }
    }

    pub fn vector(&self) -> Vector3<f64> {
        match self {
            Json::List(v) if v.len() == 3 => {
                Vector3::new(v[0].number(), v[1].number(), v[2].number())
            }
            other => panic!("not a 3-vector: {other:?}"),
        }
    }

    pub fn text(&self) -> &str {
        match self {
            Json::Text(s) => s,
            other => panic!("not a string: {other:?}"),
        }
    }
}

/// Parses a whole document (panics on malformed input: test data).
pub fn parse(text: &str) -> Json {
    Parser {
        bytes: text.as_bytes(),
        at: 0,
    }
    .value()
}
