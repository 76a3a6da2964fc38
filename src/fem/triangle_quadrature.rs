//! Quadrature on triangles: symmetric rules in barycentric coordinates (Dunavant 1985), exact for
//! polynomials up to the stated degree. Weights sum to 1 (multiply by the area).

use crate::error::InputError;

/// The symmetric orbit of a point with barycentric coordinates (a, b, b): (a, b, b), (b, a, b),
/// (b, b, a).
fn orbit(a: f64, b: f64) -> [[f64; 3]; 3] {
    [[a, b, b], [b, a, b], [b, b, a]]
}

/// A rule: barycentric points (λ1, λ2, λ3) and weights summing to 1.
#[derive(Debug, Clone, PartialEq)]
pub struct TriangleRule {
    pub points: Vec<[f64; 3]>,
    pub weights: Vec<f64>,
    pub degree: usize,
}

impl TriangleRule {
    /// The rule of (at least) `degree`, 1 ≤ degree ≤ 5: 1, 3, 4→6, 6, 7 points.
    pub fn of_degree(degree: usize) -> Result<Self, InputError> {
        let (points, weights): (Vec<[f64; 3]>, Vec<f64>) = match degree {
            1 => (vec![[1.0 / 3.0; 3]], vec![1.0]),
            2 => {
                let (a, b) = (2.0 / 3.0, 1.0 / 6.0);
                (orbit(a, b).to_vec(), vec![1.0 / 3.0; 3])
            }
            3 | 4 => {
                // Dunavant degree 4, 6 points (positive weights; used for degree 3 too).
                let (a1, b1, w1) = (0.108103018168070, 0.445948490915965, 0.223381589678011);
                let (a2, b2, w2) = (0.816847572980459, 0.091576213509771, 0.109951743655322);
                (
                    [orbit(a1, b1), orbit(a2, b2)].concat(),
                    vec![w1, w1, w1, w2, w2, w2],
                )
            }
            5 => {
                let c = 1.0 / 3.0;
                let (a1, b1, w1) = (0.059715871789770, 0.470142064105115, 0.132394152788506);
                let (a2, b2, w2) = (0.797426985353087, 0.101286507323456, 0.125939180544827);
                (
                    [[[c, c, c]].as_slice(), &orbit(a1, b1), &orbit(a2, b2)].concat(),
                    vec![0.225, w1, w1, w1, w2, w2, w2],
                )
            }
            other => {
                return Err(InputError::new(
                    "quadrature.triangle_degree",
                    other,
                    "a degree from 1 to 5",
                ))
            }
        };
        let degree = if degree == 3 { 4 } else { degree };
        Ok(Self {
            points,
            weights,
            degree,
        })
    }
}

#[cfg(test)]
mod tests {
    //! Triangle rules: exactness for monomials x^a y^b with a + b ≤ degree on the reference
    //! triangle (∫ x^a y^b = a! b! / (a + b + 2)!).
    use super::*;

    fn factorial(n: u32) -> f64 {
        (1..=n).map(|k| k as f64).product()
    }

    #[test]
    fn rules_integrate_monomials_up_to_their_degree() {
        for degree in 1..=5 {
            let rule = TriangleRule::of_degree(degree).unwrap();
            assert!((rule.weights.iter().sum::<f64>() - 1.0).abs() < 1e-13);
            for a in 0..=degree as u32 {
                for b in 0..=(degree as u32 - a) {
                    let exact = factorial(a) * factorial(b) / factorial(a + b + 2);
                    // reference triangle (0,0), (1,0), (0,1): x = λ2, y = λ3, area 1/2
                    let got: f64 = rule
                        .points
                        .iter()
                        .zip(&rule.weights)
                        .map(|(l, w)| w * l[1].powi(a as i32) * l[2].powi(b as i32))
                        .sum::<f64>()
                        * 0.5;
                    assert!(
                        (got - exact).abs() < 1e-12,
                        "degree {degree}: x^{a} y^{b}: {got} vs {exact}"
                    );
                }
            }
        }
    }

    #[test]
    fn degree_six_is_not_offered() {
        assert!(TriangleRule::of_degree(6).is_err());
    }
}
