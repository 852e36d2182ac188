//! The ladder on the aimed rule's grids ([`super::super::aimed`]): polar angles about a pole
//! aimed at the nearest point of the other body's singular set, clustered toward it, over an
//! ellipsoid X; levels step by one node, and from the third level on jump to the level the
//! observed rate of convergence predicts ([`LadderSettings::jump`]).

use super::ladder::{ladder_settings, run_ladder, FixedLadder, LadderSettings};
use super::{Problem, Strategy};
use crate::aimed;
use crate::assembly::solid_values;
use crate::body::{with_field, BodyShape};
use crate::error::InteractionError;
use crate::options::{Interaction, Request};
use crate::surface_choice::Placement;

/// The aimed rule's ladder, with its unit-sphere grids kept ([`aimed::GridCache`]). Where the
/// placement has no aim (the surface is not an ellipsoid, or the options do not ask for the
/// aimed rule), the fixed ladder.
#[derive(Debug, Clone, Default)]
pub(crate) struct AimedLadder {
    grids: aimed::GridCache,
}

impl Strategy for AimedLadder {
    fn refine(&mut self, problem: &Problem<'_>) -> Result<Interaction, InteractionError> {
        let Problem {
            x,
            y,
            placement: p,
            options,
            request,
            budget,
        } = *problem;
        if let (Some(aim), BodyShape::Disk(lamina)) = (p.lamina_aim, x.shape()) {
            return aimed::lamina::refine(&mut self.grids.lamina, problem, lamina, &aim);
        }
        let (Some(aim), BodyShape::Solid(e)) = (p.aim, x.shape()) else {
            return FixedLadder.refine(problem);
        };
        let aim = &aim;
        // The aimed nodes have no mirror symmetry.
        let p = &Placement {
            half_azimuth: false,
            half_transverse: false,
            ..*p
        };
        let start = aim.start;
        // The product rule (Gauss–Legendre in cos θ over the whole range, no split halves)
        // gains two degrees per node: a step of one node suffices.
        let settings = LadderSettings {
            jump: true,
            single_step: aim.cluster == 0,
            geometric: true,
            oscillating: aim.ring,
            ..ladder_settings(options, budget)
        };
        let grids = &mut self.grids;
        run_ladder(
            &settings,
            p,
            start,
            |level| aimed::grid_key(level, aim).size(),
            // The polar count is the level; the azimuths follow it in steps of two, and are
            // exact where the integrand is symmetric about the pole's axis.
            |from, to| {
                aim.coaxial
                    || aimed::grid_key(to, aim).azimuth() > aimed::grid_key(from, aim).azimuth()
            },
            |level| {
                let grid = grids.get(aimed::grid_key(level, aim))?;
                let sums = match (p.far, request == Request::Force) {
                    (true, true) => with_field!(&y.field, |f| aimed::aimed_sums::<_, true, false>(
                        e, &grid, aim, f, &p.map
                    )),
                    (false, true) => with_field!(
                        &y.field,
                        |f| aimed::aimed_sums::<_, false, false>(e, &grid, aim, f, &p.map)
                    ),
                    (true, false) => with_field!(&y.field, |f| aimed::aimed_sums::<_, true, true>(
                        e, &grid, aim, f, &p.map
                    )),
                    (false, false) => with_field!(
                        &y.field,
                        |f| aimed::aimed_sums::<_, false, true>(e, &grid, aim, f, &p.map)
                    ),
                };
                let mut values = solid_values(sums, x.density, p);
                values.request = request;
                Ok((values, grid.len()))
            },
        )
    }
}
