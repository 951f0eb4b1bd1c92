		 /*******************************
		 *           UPDATES            *
		 *******************************/

conjuncts(Var, _) :- var(Var), !,
    throw(error(instantiation_error, _)).
conjuncts((A, B), L) :- !,
    conjuncts(A, LA),
    conjuncts(B, LB),
    append(LA, LB, L).
conjuncts(true, []) :- !.
conjuncts(X, [X]).

%!  update(+B, +G, +Mode, +Formula, -Deleted, -Added, -Achieved) is det.
%   Mode insert: positive literals are added, not(L) deleted; delete: the inverse. All
%   additions are checked first, deletions happen first. Results are compact (Python knows
%   the literals): Deleted has, per deletion, the number of facts removed (ground literal) or
%   the list of removed instances; Added a 1 (added) or 0 (already believed) per addition.
%   When beliefs changed and there are goals, blind commitment runs too (Achieved).

update(B, G, Mode, Formula, Deleted, Added, Achieved) :-
    split_formula(Formula, Mode, Adds, [], Dels, []),
    must_be_inserted(Adds),
    delete_facts(Dels, B, Deleted, false, Changed0),
    add_facts(Adds, B, G, Added, Changed0, Changed),
    (   Changed == true,
        G:'$goal'(_, _)
    ->  blind_commitment(B, G, Achieved)
    ;   Achieved = []
    ).

%   split_formula(+Formula, +Mode, -Adds, ?AddsTail, -Dels, ?DelsTail): the facts to add and
%   to delete, each in conjunction order (`true` skipped).
split_formula(Var, _, _, _, _, _) :-
    var(Var), !,
    throw(error(instantiation_error, _)).
split_formula((A, B), Mode, Adds0, Adds, Dels0, Dels) :- !,
    split_formula(A, Mode, Adds0, Adds1, Dels0, Dels1),
    split_formula(B, Mode, Adds1, Adds, Dels1, Dels).
split_formula(true, _, Adds, Adds, Dels, Dels) :- !.
split_formula(not(P), Mode, Adds0, Adds, Dels0, Dels) :- !,
    negative(Mode, P, Adds0, Adds, Dels0, Dels).
split_formula(\+ P, Mode, Adds0, Adds, Dels0, Dels) :- !,
    negative(Mode, P, Adds0, Adds, Dels0, Dels).
split_formula(P, insert, [P|Adds], Adds, Dels, Dels) :- !.
split_formula(P, delete, Adds, Adds, [P|Dels], Dels).

negative(insert, P, Adds, Adds, [P|Dels], Dels).
negative(delete, P, [P|Adds], Adds, Dels, Dels).

delete_facts([], _, [], Changed, Changed).
delete_facts([Fact|Facts], B, [Deleted|More], Changed0, Changed) :-
    delete_fact(B, Fact, Deleted),
    (   Deleted \== 0, Deleted \== []
    ->  Changed1 = true,
        (   listening -> tell_deleted(Deleted, Fact) ; true )
    ;   Changed1 = Changed0
    ),
    delete_facts(Facts, B, More, Changed1, Changed).

add_facts([], _, _, [], Changed, Changed).
add_facts([Fact|Facts], B, G, [Added|More], Changed0, Changed) :-
    add_fact(B, G, Fact, Added),
    (   Added == 1
    ->  Changed1 = true,
        (   listening -> tell(belief(added, Fact)) ; true )
    ;   Changed1 = Changed0
    ),
    add_facts(Facts, B, G, More, Changed1, Changed).

tell_deleted(Instances, _) :-
    is_list(Instances), !,
    forall(member(Instance, Instances), tell(belief(deleted, Instance))).
tell_deleted(Copies, Fact) :-
    forall(between(1, Copies, _), tell(belief(deleted, Fact))).

must_be_inserted([]).
must_be_inserted([Fact|Facts]) :-
    must_be_fact(Fact, "insert"),
    must_be_inserted(Facts).

add_fact(B, G, Fact, Added) :-
    (   catch(clause(B:Fact, true), error(permission_error(_, _, _), _), fail)
    ->  Added = 0
    ;   assertz(B:Fact),
        ensure_dynamic(G, Fact),
        Added = 1
    ).

delete_fact(B, Fact, Deleted) :-
    must_be_callable(Fact),
    (   ground(Fact)
    ->  (   current_predicate(_, B:Fact)
        ->  retract_count(B, Fact, 0, Deleted)
        ;   Deleted = 0
        )
    ;   current_predicate(_, B:Fact)
    ->  findall(Fact, retract(B:Fact), Deleted)
    ;   Deleted = []
    ).

%   retract_count(+B, +Fact, +N0, -N): retracts every copy of the ground Fact.
retract_count(B, Fact, N0, N) :-
    (   retract(B:Fact)
    ->  N1 is N0 + 1,
        retract_count(B, Fact, N1, N)
    ;   N = N0
    ).

must_be_callable(Fact) :-
    (   fact_like(Fact)
    ->  true
    ;   var(Fact)
    ->  throw(error(instantiation_error, _))
    ;   throw(error(type_error(fact, Fact), _))
    ).

must_be_fact(Fact, Action) :-
    must_be_callable(Fact),
    (   ground(Fact)
    ->  true
    ;   format(string(M), "~w: ~q is not ground (unbound variables)", [Action, Fact]),
        throw(ga_error(M))
    ).

		 /*******************************
		 *            GOALS             *
		 *******************************/

%!  adopt(+B, +G, +Formula, -Result) is det.
%   Result: believed, exists or adopted.

adopt(B, G, Formula, Result) :-
    conjuncts(Formula, Facts),
    forall(member(F, Facts), must_be_fact(F, "adopt")),
    declare_goal(B, G, Facts),
    (   Facts == []
    ->  Result = believed
    ;   \+ \+ all_believed(B, Facts)
    ->  Result = believed
    ;   G:'$top'(Base),
        msort(Facts, Sorted),
        G:'$goal'(Base, Id),
        goal_facts(G, Id, Existing),
        msort(Existing, Sorted)
    ->  Result = exists
    ;   G:'$top'(Base),
        add_goal(G, Base, Facts),
        Result = adopted
    ).

all_believed(B, Facts) :-
    forall(member(F, Facts), B:F).

add_goal(G, Base, Facts) :-
    flag('$ga_goal_id', Id, Id + 1),
    forall(member(F, Facts), assertz(G:'$gf'(Id, F))),
    assertz(G:'$goal'(Base, Id)).

goal_facts(G, Id, Facts) :-
    findall(F, G:'$gf'(Id, F), Facts).

remove_goal(G, Id, Facts) :-
    goal_facts(G, Id, Facts),
    retractall(G:'$gf'(Id, _)),
    retractall(G:'$goal'(_, Id)).

%!  drop(+B, +G, +Formula, -Removed) is det.
%   Removes every goal of the top goal base from which Formula follows.

drop(B, G, Formula, Removed) :-
    declare(B, G, [Formula]),
    G:'$top'(Base),
    findall(Id, ( G:'$goal'(Base, Id),
                  \+ \+ ( b_setval('$ga_g', Id), G:Formula ) ), Ids),
    maplist(remove_goal(G), Ids, Removed).

%!  blind_commitment(+B, +G, -Removed) is det.
%   Removes every goal (all goal bases) whose facts are all believed.

blind_commitment(B, G, Removed) :-
    (   G:'$goal'(_, Id),
        achieved(B, G, Id)
    ->  findall(Id1, ( G:'$goal'(_, Id1), achieved(B, G, Id1) ), Ids),
        maplist(remove_goal(G), Ids, Removed),
        (   listening
        ->  forall(member(Goal, Removed), tell(goal(achieved, Goal)))
        ;   true
        )
    ;   Removed = []
    ).

%!  recheck(+B) is det.
%   Percepts, messages or goal bases changed: the next action (or check_goals/3) checks
%   every goal. The flag is a global variable named after the belief module.
recheck(B) :-
    nb_setval(B, true).

%!  check_goals(+B, +G, -Removed) is det.
%   Blind commitment when something other than an update may have achieved goals.
check_goals(B, G, Removed) :-
    (   nb_getval(B, true)
    ->  nb_setval(B, false),
        blind_commitment(B, G, Removed)
    ;   Removed = []
    ).

achieved(B, G, Id) :-
    \+ ( G:'$gf'(Id, Fact), \+ B:Fact ).

%!  goals(+G, -Goals) is det.
goals(G, Goals) :-
    G:'$top'(Base),
    findall(Facts, ( G:'$goal'(Base, Id), goal_facts(G, Id, Facts) ), Goals).

%!  push(+B, +G, +Goals) is det.
push(B, G, Goals) :-
    maplist(conjuncts_or_list, Goals, FactLists),
    forall(( member(Facts, FactLists), member(F, Facts) ), must_be_fact(F, "goal")),
    forall(member(Facts, FactLists), declare_goal(B, G, Facts)),
    retract(G:'$top'(Base0)),
    Base is Base0 + 1,
    assertz(G:'$top'(Base)),
    forall(member(Facts, FactLists), add_goal(G, Base, Facts)),
    recheck(B).

conjuncts_or_list(Goal, Facts) :-
    (   is_list(Goal)
    ->  Facts = Goal
    ;   conjuncts(Goal, Facts)
    ).

%!  pop(+G, -Goals) is det.
pop(G, Goals) :-
    G:'$top'(Base),
    (   Base > 0
    ->  findall(Id, G:'$goal'(Base, Id), Ids),
        maplist(remove_goal(G), Ids, Goals),
        retract(G:'$top'(Base)),
        Base1 is Base - 1,
        assertz(G:'$top'(Base1))
    ;   throw(ga_error("pop_goal_base: only the agent's own goal base is left"))
    ).

		 /*******************************
		 *   BELIEFS, PERCEPTS, MAIL    *
		 *******************************/

%!  beliefs(+B, -Facts) is det.
%   Facts of B's dynamic predicates, except knowledge predicates, percepts and internals;
%   predicates in standard order of Name/Arity, facts in clause order.

beliefs(B, Facts) :-
    findall(N/A, ( current_predicate(B:N/A),
                   \+ sub_atom(N, 0, _, _, '$'),
                   N/A \== percept/1,
                   \+ B:'$kpred'(N/A),
                   functor(Head, N, A),
                   predicate_property(B:Head, dynamic),
                   \+ predicate_property(B:Head, imported_from(_))
                 ), PIs0),
    msort(PIs0, PIs),
    findall(Head, ( member(N/A, PIs),
                    functor(Head, N, A),
                    clause(B:Head, true)
                  ), Facts).

%!  set_percepts(+B, +Percepts) is det.
set_percepts(B, Percepts) :-
    retractall(B:percept(_)),
    forall(member(P, Percepts), assertz(B:percept(P))),
    recheck(B).

%!  percepts(+B, -Percepts) is det.
percepts(B, Percepts) :-
    findall(P, B:percept(P), Percepts).

%!  add_once(+B, +Fact, -Added) is det.
%   Asserts Fact unless already there; Added is true or false.

add_once(B, Fact, Added) :-
    recheck(B),
    (   clause(B:Fact, true)
    ->  Added = false
    ;   assertz(B:Fact),
        Added = true
    ).

%!  set_identity(+B, +G, +Me, +Agents) is det.
%   B believes me(Me) and agent(A) for each of Agents (its own copy of the list).
set_identity(B, _G, Me, Agents) :-
    retractall(B:me(_)),
    retractall(B:agent(_)),
    assertz(B:me(Me)),
    forall(member(A, Agents), assertz(B:agent(A))),
    recheck(B).

%!  new_directory(+S) is det.
%   Creates module S holding agent/1 for the agents of one system, shared by all of them.
new_directory(S) :-
    set_module(S:class(temporary)),
    set_module(S:base(system)),
    dynamic(S:agent/1).

%!  directory_add(+S, +Agent) is det.
directory_add(S, Agent) :-
    assertz(S:agent(Agent)).

%!  join_directory(+B, +Me, +S) is det.
%   B believes me(Me), and agent/1 answers from directory S (one list per system: joining is
%   O(1) and the list is stored once, however many agents there are).
join_directory(B, Me, S) :-
    retractall(B:me(_)),
    retractall(B:agent(_)),
    retractall(B:'$ga_dir'(_)),
    assertz(B:me(Me)),
    assertz(B:'$ga_dir'(S)),
    assertz(B:(agent(A) :- '$ga_dir'(D), D:agent(A))),
    recheck(B).

%!  destroy_directory(+S) is det.
destroy_directory(S) :-
    '$destroy_module'(S).
