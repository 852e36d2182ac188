//! Every body against committed high-precision reference values.
//!
//! The values in `tests/reference/potentials.json` (workspace root) come from
//! `tests/reference/potentials.py`, which evaluates $\Phi$ and $\mathbf a = -\nabla\Phi$ at 40
//! significant digits by routes independent of the closed forms in this crate: the Dirichlet
//! integral for the solids, ring and rim integrals for the disk (provenance, accuracy and the
//! validation against brute-force volume integrals in `tests/reference/README.md`). The inputs
//! are exact doubles and every number is a decimal string, read with `str::parse::<f64>`
//! (correctly rounded), so the reference and the code evaluate at the same point.
//!
//! For each case the test measures
//! $|\Phi - \Phi\_\mathrm{ref}| / |\Phi\_\mathrm{ref}|$ and
//! $\lVert\mathbf a - \mathbf a\_\mathrm{ref}\rVert / \lVert\mathbf a\_\mathrm{ref}\rVert$ and
//! holds them to [`tolerance::POTENTIAL_REL`] and [`tolerance::ACCELERATION_REL`], outside,
//! inside a solid and on a disk's lamina alike. One test per body kind; each prints the worst
//! case per shape (`cargo test -p surfgrav-potentials --test reference_values -- --nocapture`)
//! and, on failure, lists every failing case rather than the first.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use serde_json::Value;
use surfgrav_potentials::{
    tolerance, BodyError, Ellipsoid, PointMass, Potential, Region, Sphere, Spheroid, UniformDisk,
    Vec3,
};

/// One reference case, numbers already parsed.
#[derive(Debug)]
struct Case {
    body: String,
    params: BTreeMap<String, f64>,
    point: Vec3,
    region: String,
    label: String,
    potential: f64,
    acceleration: Vec3,
}

fn reference_path() -> String {
    format!(
        "{}/../../tests/reference/potentials.json",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// A decimal string of the JSON file as a double (correctly rounded by `str::parse`).
fn number(value: &Value, what: &str) -> f64 {
    let text = value
        .as_str()
        .unwrap_or_else(|| panic!("{what}: expected a decimal string, got {value}"));
    text.parse::<f64>()
        .unwrap_or_else(|e| panic!("{what}: cannot parse {text:?}: {e}"))
}

fn vector(value: &Value, what: &str) -> Vec3 {
    let items = value
        .as_array()
        .unwrap_or_else(|| panic!("{what}: expected an array of 3, got {value}"));
    assert_eq!(items.len(), 3, "{what}: expected 3 components");
    Vec3::new(
        number(&items[0], what),
        number(&items[1], what),
        number(&items[2], what),
    )
}

fn cases() -> &'static [Case] {
    static CASES: OnceLock<Vec<Case>> = OnceLock::new();
    CASES.get_or_init(|| {
        let path = reference_path();
        let text = std::fs::read_to_string(&path)
            .unwrap_or_else(|e| panic!("cannot read the reference file {path}: {e}"));
        let doc: Value =
            serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path} is not valid JSON: {e}"));
        let list = doc["cases"]
            .as_array()
            .unwrap_or_else(|| panic!("{path}: no `cases` array"));
        list.iter()
            .map(|c| {
                let label = c["label"]
                    .as_str()
                    .expect("case without a label")
                    .to_owned();
                let params = c["params"]
                    .as_object()
                    .unwrap_or_else(|| panic!("{label}: no params"))
                    .iter()
                    .map(|(k, v)| (k.clone(), number(v, &label)))
                    .collect();
                Case {
                    body: c["body"].as_str().expect("case without a body").to_owned(),
                    params,
                    point: vector(&c["point"], &label),
                    region: c["region"]
                        .as_str()
                        .expect("case without a region")
                        .to_owned(),
                    potential: number(&c["potential"], &label),
                    acceleration: vector(&c["acceleration"], &label),
                    label,
                }
            })
            .collect()
    })
}

impl Case {
    fn param(&self, name: &str) -> f64 {
        *self
            .params
            .get(name)
            .unwrap_or_else(|| panic!("{}: missing parameter {name}", self.label))
    }

    /// The body this case describes, built through the public constructors.
    fn build(&self) -> Result<Box<dyn Potential>, BodyError> {
        let mass = self.param("mass");
        let g = self.param("g");
        Ok(match self.body.as_str() {
            "point" => Box::new(PointMass::new(mass)?.with_gravitational_constant(g)?),
            "sphere" => {
                Box::new(Sphere::new(self.param("radius"), mass)?.with_gravitational_constant(g)?)
            }
            "spheroid" => Box::new(
                Spheroid::new(
                    self.param("equatorial_radius"),
                    self.param("polar_radius"),
                    mass,
                )?
                .with_gravitational_constant(g)?,
            ),
            "ellipsoid" => Box::new(
                Ellipsoid::new(self.param("a"), self.param("b"), self.param("c"), mass)?
                    .with_gravitational_constant(g)?,
            ),
            "disk" => Box::new(
                UniformDisk::new(self.param("radius"), mass)?.with_gravitational_constant(g)?,
            ),
            other => panic!("{}: unknown body kind {other}", self.label),
        })
    }

    /// The shape the case belongs to: the label up to its colon ("spheroid c/a=0.25").
    fn shape(&self) -> &str {
        self.label.split(':').next().unwrap_or(&self.label)
    }

    fn expected_region(&self) -> Region {
        match self.region.as_str() {
            "outside" => Region::Outside,
            "inside" => Region::Inside,
            "surface" => Region::OnSurface,
            other => panic!("{}: unknown region {other}", self.label),
        }
    }
}

/// Worst errors seen over a group of cases, with the label where each occurred.
#[derive(Default)]
struct Worst {
    cases: usize,
    potential: (f64, String),
    acceleration: (f64, String),
}

impl Worst {
    fn add(&mut self, label: &str, potential_err: f64, acceleration_err: f64) {
        self.cases += 1;
        // A NaN error is recorded as the worst.
        if potential_err.is_nan() || potential_err > self.potential.0 {
            self.potential = (potential_err, label.to_owned());
        }
        if acceleration_err.is_nan() || acceleration_err > self.acceleration.0 {
            self.acceleration = (acceleration_err, label.to_owned());
        }
    }
}

/// `error <= tolerance`, false for a NaN error.
fn within(error: f64, tolerance: f64) -> bool {
    error <= tolerance
}

fn relative(got: f64, expected: f64) -> f64 {
    (got - expected).abs() / expected.abs()
}

/// Checks every case of one body kind; prints the worst case per shape and panics listing all
/// failures.
fn check_body_kind(kind: &str, minimum_cases: usize) {
    let selected: Vec<&Case> = cases().iter().filter(|c| c.body == kind).collect();
    assert!(
        selected.len() >= minimum_cases,
        "only {} {kind} cases in {} (expected at least {minimum_cases})",
        selected.len(),
        reference_path()
    );

    let mut failures = Vec::new();
    let mut region_mismatches = Vec::new();
    let mut by_shape: BTreeMap<String, Worst> = BTreeMap::new();
    let mut by_region: BTreeMap<String, Worst> = BTreeMap::new();

    for case in &selected {
        let body = match case.build() {
            Ok(body) => body,
            Err(e) => {
                failures.push(format!("{}: construction failed: {e}", case.label));
                continue;
            }
        };
        let field = body.field(&case.point);
        let potential_err = relative(field.potential, case.potential);
        let acceleration_err =
            (field.acceleration - case.acceleration).norm() / case.acceleration.norm();

        by_shape.entry(case.shape().to_owned()).or_default().add(
            &case.label,
            potential_err,
            acceleration_err,
        );
        by_region.entry(case.region.clone()).or_default().add(
            &case.label,
            potential_err,
            acceleration_err,
        );

        if !within(potential_err, tolerance::POTENTIAL_REL) {
            failures.push(format!(
                "{} [{}] at {:?}: potential expected {:e}, got {:e}, relative error {:.2e}",
                case.label,
                case.region,
                case.point.as_slice(),
                case.potential,
                field.potential,
                potential_err
            ));
        }
        if !within(acceleration_err, tolerance::ACCELERATION_REL) {
            failures.push(format!(
                "{} [{}] at {:?}: acceleration expected {:?}, got {:?}, relative error {:.2e}",
                case.label,
                case.region,
                case.point.as_slice(),
                case.acceleration.as_slice(),
                field.acceleration.as_slice(),
                acceleration_err
            ));
        }
        let region = body.region(&case.point);
        if region != case.expected_region() {
            region_mismatches.push(format!(
                "{}: region() says {region:?}, reference says {}",
                case.label, case.region
            ));
        }
    }

    println!(
        "\n{kind}: {} cases, tolerances Φ {:.0e}, a {:.0e}",
        selected.len(),
        tolerance::POTENTIAL_REL,
        tolerance::ACCELERATION_REL
    );
    println!(
        "{:<34} {:>5}  {:>9}  {:>9}  worst Φ case / worst a case",
        "shape", "cases", "Φ rel", "a rel"
    );
    for (name, worst) in by_shape.iter().chain(by_region.iter()) {
        println!(
            "{:<34} {:>5}  {:>9.2e}  {:>9.2e}  {} / {}",
            name,
            worst.cases,
            worst.potential.0,
            worst.acceleration.0,
            worst.potential.1,
            worst.acceleration.1
        );
    }
    if !region_mismatches.is_empty() {
        println!(
            "note: {} region() answers differ from the reference classification \
             (not an accuracy failure):",
            region_mismatches.len()
        );
        for line in &region_mismatches {
            println!("  {line}");
        }
    }

    assert!(
        failures.is_empty(),
        "{} of {} {kind} checks fail against {}:\n{}",
        failures.len(),
        2 * selected.len(),
        reference_path(),
        failures.join("\n")
    );
}

#[test]
fn point_mass_matches_reference() {
    check_body_kind("point", 8);
}

#[test]
fn sphere_matches_reference() {
    check_body_kind("sphere", 40);
}

#[test]
fn spheroid_matches_reference() {
    check_body_kind("spheroid", 300);
}

#[test]
fn ellipsoid_matches_reference() {
    check_body_kind("ellipsoid", 150);
}

#[test]
fn disk_matches_reference() {
    check_body_kind("disk", 40);
}

/// The reference file itself: unique labels, finite values, inputs that round-trip, and the
/// spread of shapes the accuracy claim covers.
#[test]
fn reference_file_is_well_formed() {
    let all = cases();
    let mut labels = std::collections::BTreeSet::new();
    for case in all {
        assert!(
            labels.insert(case.label.as_str()),
            "duplicate label {}",
            case.label
        );
        assert!(
            case.potential.is_finite() && case.potential < 0.0,
            "{}: potential {} must be finite and negative",
            case.label,
            case.potential
        );
        assert!(
            case.acceleration.iter().all(|v| v.is_finite()) && case.acceleration.norm() > 0.0,
            "{}: acceleration must be finite and non-zero",
            case.label
        );
        // The acceleration points toward the body: a · r < 0 for every point of the file
        // (origin-centred convex bodies).
        assert!(
            case.acceleration.dot(&case.point) < 0.0,
            "{}: reference acceleration does not point toward the body",
            case.label
        );
    }
    for kind in ["point", "sphere", "spheroid", "ellipsoid", "disk"] {
        assert!(
            all.iter().any(|c| c.body == kind && c.region == "outside"),
            "no outside {kind} case"
        );
    }
    for kind in ["sphere", "spheroid", "ellipsoid"] {
        assert!(
            all.iter().any(|c| c.body == kind && c.region == "inside"),
            "no inside {kind} case"
        );
    }
}
