% affordance.pl -- affordance knowledge for GOAL agents (thesis chapter 6).
%
% A plain clause library without a module declaration: the runtime adds these clauses to the
% agent's own module next to its knowledge, so every predicate below sees the agent's beliefs
% afford(Obj, Act, Eff, Tot, Suc, Rel) (eq. 6.1) and its knowledge. It uses only built-ins
% (no library imports, no directives), so it loads the same whether consulted or asserted.
%
% Parameters (thesis defaults)     r0 = 0.1   reliability of an unverified affordance (6.5)
%                                  r1 = 0.3   reliability the learner reports for "predicted
%                                             effective" (6.11)
%                                  r2 = 0.05  reliability it reports for "predicted not
%                                             effective" (6.14)
%                                  tau = 0.6  threshold of a reliable affordance (6.2)
% Read them with afford_param(Name, Value). To override one, an agent states a fact in its
% knowledge section:
%     knowledge{ afford_setting(tau, 0.7). }
% afford_setting/2 is the agent's own predicate (this library defines no clause for it), so
% the override never clashes with the defaults: a setting wins, a missing setting falls back
% to the default. Every lookup checks 0 < r2 < r0 < r1 < tau < 1 and rejects unknown names
% with a domain_error that says what is wrong.
%
% Merging a percept into the belief base (eq. 6.3) is ONE event-module rule, plus one that
% adopts a percept about an affordance not believed yet (tests/robot/test_affordance_agent.py runs
% exactly these two in a GOAL agent):
%     event module { program {
%         forall bel(percept(afford(O, A, E, T1, S1, R1)), afford(O, A, E, T, S, R),
%                    afford_merge(afford(O, A, E, T, S, R), afford(O, A, E, T1, S1, R1),
%                                 afford(O, A, E, T2, S2, R2)))
%             do delete(afford(O, A, E, T, S, R)) + insert(afford(O, A, E, T2, S2, R2)).
%         forall bel(percept(afford(O, A, E, T, S, R)), not(afford(O, A, E, _, _, _)))
%             do insert(afford(O, A, E, T, S, R)).
%     } }
% Load the library with  #import "affordance.pl".  in the init module.
%
% Predicate overview (Obj, Act, Eff always in the order of afford/6):
%     afford_param(?Name, ?Value)           a parameter, the agent's setting or the default
%     afford_merge(+Old, +Percept, -New)    eq. 6.3
%     afford_reliable(?Obj, ?Act, ?Eff)     Rel >= tau (usable by rule 6.2)
%     afford_best(?Obj, -Act, ?Eff)         the most reliable reliable action (rule 6.2)
%     afford_roulette(+Obj, -Act, +Eff)     reliability-proportional choice (§6.3.4)
%     afford_spin(+Wheel, -Act)             the same over an agent's own list of Rel-Act
%     afford_learning_needed(?Obj, ?Eff)    rule 6.4's band: nothing reliable, not exhausted
%     afford_to_verify(?Obj, ?Act, ?Eff)    rule 6.12's band: r1 =< Rel < tau
%     afford_learning_exhausted(?Obj, ?Eff) every Rel < r2 (termination, §6.3.4)

% afford_default(?Name, ?Value): the thesis's values (§6.3.2, §6.3.4).
afford_default(r0, 0.1).
afford_default(r1, 0.3).
afford_default(r2, 0.05).
afford_default(tau, 0.6).

% afford_param(?Name, ?Value): parameter Name, from the agent's afford_setting/2 when present.
afford_param(Name, Value) :-
    afford_params(R0, R1, R2, Tau),
    afford_param_pick(Name, Value, R0, R1, R2, Tau).

afford_param_pick(r0, R0, R0, _, _, _).
afford_param_pick(r1, R1, _, R1, _, _).
afford_param_pick(r2, R2, _, _, R2, _).
afford_param_pick(tau, Tau, _, _, _, Tau).

% afford_params(-R0, -R1, -R2, -Tau): all four parameters, checked for a usable ordering.
afford_params(R0, R1, R2, Tau) :-
    afford_check_setting_names,
    afford_raw_param(r0, R0),
    afford_raw_param(r1, R1),
    afford_raw_param(r2, R2),
    afford_raw_param(tau, Tau),
    (   number(R0), number(R1), number(R2), number(Tau),
        0 < R2, R2 < R0, R0 < R1, R1 < Tau, Tau < 1
    ->  true
    ;   throw(error(domain_error('0 < r2 < r0 < r1 < tau < 1', [r2=R2, r0=R0, r1=R1, tau=Tau]),
                    context(afford_param/2,
                            'affordance parameters must be numbers in this order; \c
                             set them with afford_setting/2 in the agent\'s knowledge')))
    ).

% afford_raw_param(+Name, -Value): the agent's first setting for Name, else the default.
afford_raw_param(Name, Value) :-
    (   current_predicate(afford_setting/2), afford_setting(Name, Set)
    ->  Value = Set
    ;   afford_default(Name, Value)
    ).

% afford_check_setting_names: every afford_setting/2 fact names a known parameter.
afford_check_setting_names :-
    (   current_predicate(afford_setting/2),
        afford_setting(Name, _),
        \+ ( atom(Name), afford_default(Name, _) )
    ->  throw(error(domain_error('an affordance parameter: r0, r1, r2 or tau', Name),
                    context(afford_param/2, 'unknown parameter in afford_setting/2')))
    ;   true
    ).

% afford_belief(?Obj, ?Act, ?Eff, ?Tot, ?Suc, ?Rel): a believed affordance; none when the
% agent never declared or inserted afford/6 (so the predicates below fail instead of raising).
afford_belief(Obj, Act, Eff, Tot, Suc, Rel) :-
    current_predicate(afford/6),
    afford(Obj, Act, Eff, Tot, Suc, Rel).

% afford_merge(+Old, +Percept, -New): eq. 6.3. Counts add up and the reliability moves
% towards the percept's by 1/(Tot+1), Tot being the old count.
afford_merge(afford(Obj, Act, Eff, Tot, Suc, Rel),
             afford(Obj, Act, Eff, Tot1, Suc1, Rel1),
             afford(Obj, Act, Eff, Tot2, Suc2, Rel2)) :-
    Tot2 is Tot + Tot1,
    Suc2 is Suc + Suc1,
    Rel2 is Rel + (Rel1 - Rel) / (Tot + 1).

% afford_reliable(?Obj, ?Act, ?Eff): a believed affordance with Rel >= tau.
afford_reliable(Obj, Act, Eff) :-
    afford_param(tau, Tau),
    afford_belief(Obj, Act, Eff, _, _, Rel),
    Rel >= Tau.

% afford_best(?Obj, -Act, ?Eff): the reliable action with the highest reliability for Obj and
% Eff, the first believed one on ties (rule 6.2 and the choice rule below it in §6.3.2).
afford_best(Obj, Act, Eff) :-
    afford_param(tau, Tau),
    afford_object_effect(Obj, Eff),
    findall(Rel-A, (afford_belief(Obj, A, Eff, _, _, Rel), Rel >= Tau), [First|Rest]),
    afford_highest(Rest, First, _-Act).

% afford_highest(+Pairs, +Best0, -Best): the first Rel-Act pair with the highest Rel.
afford_highest([], Best, Best).
afford_highest([Rel-A|Rest], Rel0-A0, Best) :-
    (   Rel > Rel0
    ->  afford_highest(Rest, Rel-A, Best)
    ;   afford_highest(Rest, Rel0-A0, Best)
    ).

% afford_object_effect(?Obj, ?Eff): each believed Obj-Eff pair once.
afford_object_effect(Obj, Eff) :-
    findall(Obj-Eff, afford_belief(Obj, _, Eff, _, _, _), Pairs),
    sort(Pairs, Unique),
    afford_member(Obj-Eff, Unique).

afford_member(X, [X|_]).
afford_member(X, [_|Rest]) :-
    afford_member(X, Rest).

% afford_roulette(+Obj, -Act, +Eff): an action for Obj and Eff drawn with probability
% proportional to its reliability (roulette wheel, §6.3.4). Uses Prolog's random generator,
% seeded by the runtime with set_random(seed(N)). Fails when no affordance has Rel > 0.
afford_roulette(Obj, Act, Eff) :-
    (   ground(Obj-Eff)
    ->  true
    ;   throw(error(instantiation_error,
                    context(afford_roulette/3, 'afford_roulette/3 needs Obj and Eff bound')))
    ),
    findall(Rel-A, afford_belief(Obj, A, Eff, _, _, Rel), Wheel),
    afford_spin(Wheel, Act).

% afford_spin(+Wheel, -Act): one spin of a roulette wheel given as a list of Rel-Act pairs,
% for agents that build their own wheel (e.g. only the actions not explored yet). Act is
% drawn with probability Rel / (sum of Rel); pairs with Rel =< 0 are never drawn; fails when
% no pair has Rel > 0.
afford_spin(Wheel, Act) :-
    findall(Rel-A, ( afford_member(Rel-A, Wheel), Rel > 0 ), Live),
    afford_wheel_total(Live, 0, Total),
    Total > 0,
    Spin is random_float * Total,
    afford_wheel_pick(Live, Spin, Chosen),
    Act = Chosen.

% afford_wheel_total(+Wheel, +Sum0, -Total): the sum of the wheel's reliabilities.
afford_wheel_total([], Total, Total).
afford_wheel_total([Rel-_|Rest], Sum0, Total) :-
    Sum is Sum0 + Rel,
    afford_wheel_total(Rest, Sum, Total).

% afford_wheel_pick(+Wheel, +Spin, -Act): the slot the spin lands in (the last one absorbs
% rounding at the wheel's end).
afford_wheel_pick([Rel-A|Rest], Spin, Act) :-
    (   ( Spin < Rel ; Rest == [] )
    ->  Act = A
    ;   Spin1 is Spin - Rel,
        afford_wheel_pick(Rest, Spin1, Act)
    ).

% afford_learning_needed(?Obj, ?Eff): rule 6.4's band for the object: affordances for Obj and
% Eff are believed, none is reliable (Rel >= tau), and learning is not exhausted.
afford_learning_needed(Obj, Eff) :-
    afford_object_effect(Obj, Eff),
    \+ afford_reliable(Obj, _, Eff),
    \+ afford_learning_exhausted(Obj, Eff).

% afford_to_verify(?Obj, ?Act, ?Eff): rule 6.12's band: r1 =< Rel < tau, an affordance the
% learner predicted effective that still has to prove itself with theta_max (6.13).
afford_to_verify(Obj, Act, Eff) :-
    afford_param(r1, R1),
    afford_param(tau, Tau),
    afford_belief(Obj, Act, Eff, _, _, Rel),
    Rel >= R1,
    Rel < Tau.

% afford_learning_exhausted(?Obj, ?Eff): affordances for Obj and Eff are believed and every
% one has Rel < r2, so learning on Obj stops for good (§6.3.4, termination). Under eq. 6.3 a
% learning percept (Tot 0) never lowers a reliability below r2: r0 merged with r2 is exactly
% r2, and a used affordance only approaches r2 from above. Only failed verifications
% (afford(..., 1, 0, 0)) take an affordance below r2.
afford_learning_exhausted(Obj, Eff) :-
    afford_param(r2, R2),
    afford_object_effect(Obj, Eff),
    \+ ( afford_belief(Obj, _, Eff, _, _, Rel), Rel >= R2 ).
