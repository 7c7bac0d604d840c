// The lcp method's impact law across simultaneous contacts (`impacts =
// sequential`, the default): the step's impacts are taken one at a time,
// as Guendelman, Bridson and Fedkiw's collision pass does ("Nonconvex rigid
// bodies with stacking", SIGGRAPH 2003), and the one LCP of the step then
// solves the contacts with the velocities those impacts leave as targets.
//
// One LCP with v_n+ >= -e v_n- per contact is a simultaneous impact law: in
// a row of touching bodies struck at one end only the first pair approaches,
// the others get v_n+ >= 0 and the strike spreads over the row (e = 1: the
// rows of 2-6 left 0.66-0.72 v0 off Newton's cradle; docs/methods/lcp.md).
// Here, on the normal rows of the contact components that hold a point with
// restitution (sequential_impacts.h, steps 1 and 2):
//  1. from the velocities at the step's start, each body pair with a point
//     approaching faster than restitution_threshold collides to Newton's
//     law, pair after pair until none approaches;
//  2. a normal row that took part (received an impulse in 1.) gets as its
//     rhs the normal velocity it leaves 1. with; a contact traced to its
//     moment of impact (PredictImpact, lcp_contact_rows.h) leaves at
//     -e vc + a s where Newton's law at the step's start gives -e vn-, and
//     its rhs is shifted by the difference; the rows that took no part
//     keep their rule (lcp_contact_rows.h);
//  3. the impulses of 1. are the rows' warm start (pgs), so a row of
//     touching bodies, whose targets fix every relative velocity, starts at
//     its answer.
// A gap the step does not close (Impact::misses) makes no impact. For a
// lone pair 1.-2. give Newton's law as before (-e vc + a s), and components
// without restitution are left alone.
#pragma once

#include <vector>

#include "service/collision/contact.h"
#include "service/contact/constraint_row.h"
#include "service/contact/lcp/lcp_contact_rows.h"
#include "service/contact/sequential_impacts.h"
#include "service/physics/world.h"

namespace contactsim {

// Sets the rhs of the contacts' normal rows (rows[3 k]) that take part in
// the impacts and writes their impulse in `impulses` (per contact, N s;
// -1 for a contact without one). `before` holds the velocities at the
// step's start. Returns whether any row took part.
bool SequenceImpacts(const ContactSet& contacts, const World& world, const std::vector<SolverBody>& before,
                     const std::vector<Impact>& impacts, double threshold, SequentialImpacts* sequence,
                     std::vector<ConstraintRow>* rows, std::vector<double>* impulses);

}  // namespace contactsim
