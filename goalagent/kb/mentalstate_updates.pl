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
        may_achieve(G, Adds)
    ->  blind_commitment(B, G, Achieved)
    ;   Achieved = []
    ).

%!  update_facts(+B, +G, +Listen, +Dels, +Adds) is det.
%   As update/7 for a formula split when its rule was compiled (see compile_update/2):
%   Dels and Adds are facts whose predicates the agent declared when it was loaded.

update_facts(B, G, Listen, Dels, Adds) :-
    must_be_ground(Adds),
    delete_known(Dels, B, Listen, false, Changed0),
    add_known(Adds, B, Listen, Changed0, Changed),
    (   Changed == true,
        may_achieve(G, Adds)
    ->  blind_commitment(B, G, _)
    ;   true
    ).

%!  insert_one(+B, +G, +Listen, +Fact, +Key, +K, +Firing) is semidet.
%   insert/1 of one fact of a dynamic predicate Key (Name/Arity) the agent declared, by
%   action K of Firing: as update/7; a fact that is not ground is a problem (the action
%   is not enabled), told here rather than thrown.
insert_one(B, G, Listen, Fact, Key, K, Firing) :-
    (   ground(Fact)
    ->  true
    ;   format(string(Message), "insert: ~q is not ground (unbound variables)", [Fact]),
        problem(action(Firing, K, ga_error(Message))),
        fail
    ),
    insert_ground(B, G, Listen, Fact, Key).

%!  insert_ground(+B, +G, +Listen, +Fact, +Key) is det.
%   insert_one/7 of a Fact known to be ground (the rule's code tested its variables
%   inline, see rules.pl's update_goal/9).
insert_ground(B, G, Listen, Fact, Key) :-
    (   clause(B:Fact, true)
    ->  true
    ;   assertz(B:Fact),
        (   Listen == true -> tell(belief(added, Fact)) ; true ),
        nb_getval(G, Watched),
        (   Watched \== [],
            ( Watched == any -> true ; memberchk(Key, Watched) )
        ->  blind_commitment(B, G, _)
        ;   true
        )
    ).

%!  delete_one(+B, +G, +Listen, +Fact) is det.
%   delete/1 of one fact of a dynamic predicate the agent declared: as update/7.
delete_one(B, G, Listen, Fact) :-
    (   ground(Fact)
    ->  delete_ground(B, G, Listen, Fact)
    ;   findall(Fact, retract(B:Fact), Deleted),
        (   Deleted == []
        ->  true
        ;   (   Listen == true -> tell_deleted(Deleted, Fact) ; true ),
            (   nb_getval(G, any) -> blind_commitment(B, G, _) ; true )
        )
    ).

%!  delete_ground(+B, +G, +Listen, +Fact) is det.
%   delete_one/4 of a ground Fact (see insert_ground/5). The other copies of the fact go
%   too, by retract/1, which takes facts only: retractall/1 would also take the belief
%   rules whose head unifies with it (and did, untraced only).
delete_ground(B, G, Listen, Fact) :-
    (   retract(B:Fact)
    ->  retract_count(B, Fact, 1, Copies),
        (   Listen == true -> tell_deleted(Copies, Fact) ; true ),
        (   nb_getval(G, any) -> blind_commitment(B, G, _) ; true )
    ;   true
    ).

must_be_ground([]).
must_be_ground([Fact|Facts]) :-
    (   ground(Fact)
    ->  must_be_ground(Facts)
    ;   must_be_fact(Fact, "insert")
    ).

delete_known([], _, _, Changed, Changed).
delete_known([Fact|Facts], B, Listen, Changed0, Changed) :-
    (   ground(Fact)
    ->  retract_count(B, Fact, 0, Deleted),
        (   Deleted > 0
        ->  Changed1 = true,
            (   Listen == true -> tell_deleted(Deleted, Fact) ; true )
        ;   Changed1 = Changed0
        )
    ;   findall(Fact, retract(B:Fact), Deleted),
        (   Deleted \== []
        ->  Changed1 = true,
            (   Listen == true -> tell_deleted(Deleted, Fact) ; true )
        ;   Changed1 = Changed0
        )
    ),
    delete_known(Facts, B, Listen, Changed1, Changed).

add_known([], _, _, Changed, Changed).
add_known([Fact|Facts], B, Listen, Changed0, Changed) :-
    (   catch(clause(B:Fact, true), error(permission_error(_, _, _), _), fail)
    ->  Changed1 = Changed0
    ;   assertz(B:Fact),
        Changed1 = true,
        (   Listen == true -> tell(belief(added, Fact)) ; true )
    ),
    add_known(Facts, B, Listen, Changed1, Changed).

%   may_achieve(+G, +Adds): beliefs changed by adding (some of) Adds and deleting facts;
%   a goal may now be achieved. Goal facts are positive and ground: a goal whose
%   predicates are plain beliefs (facts only, see watch_key/3) can only be achieved by
%   adding one of its facts; any other goal by any change. The global variable named
%   after G holds what the goals watch (see watch/1).
may_achieve(G, Adds) :-
    nb_getval(G, Watched),
    (   Watched == any
    ->  true
    ;   Watched \== [],
        member(Fact, Adds),
        functor(Fact, Name, Arity),
        memberchk(Name/Arity, Watched)
    ->  true
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
    ;   catch(assertz(B:Fact), error(permission_error(modify, _, _), _),
              ( ensure_dynamic(B, Fact), assertz(B:Fact) )),  % SWI's name: make it the agent's
        ensure_dynamic(G, Fact),
        (   Fact = (_ :- _)                 % a rule: goals may now follow from anything
        ->  assertz(G:'$rule_inserted'),
            watch(G)
        ;   true
        ),
        Added = 1
    ).

%   A predicate not defined in B fails to retract, as one without clauses does.
delete_fact(B, Fact, Deleted) :-
    must_be_callable(Fact),
    (   ground(Fact)
    ->  retract_count(B, Fact, 0, Deleted)
    ;   findall(Fact, retract(B:Fact), Deleted)
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
    must_be_facts(Facts, "adopt"),
    declare_goal(B, G, Facts),
    (   Facts == []
    ->  Result = believed
    ;   \+ \+ all_believed(Facts, B)
    ->  Result = believed
    ;   add_unless_there(B, G, Facts, Result)
    ).

add_unless_there(B, G, Facts, Result) :-
    G:'$top'(Base),
    msort(Facts, Key),
    (   G:'$goal'(Base, _, Key)
    ->  Result = exists
    ;   add_goal(B, G, Base, Facts, Key),
        Result = adopted
    ).

%!  adopt_checked(+B, +G, +Formula, +Seed, -Result, -Seeded) is det.
%   adopt/4 for Python (an agent's goals section, the API): checking whether the goal is
%   believed is bounded by the agent's --max-inferences, and a check that passes a limit
%   or raises an error is not a belief -- the goal is adopted all the same (as a rule whose
%   condition does is not applicable), Result = unchecked(Message) saying why. Seed: the
%   random seed Python holds back (an integer, or none), given to set_random/1 before a
%   check that may run agent code (Seeded = true); a check of facts alone runs none.
adopt_checked(B, G, Formula, Seed, Result, Seeded) :-
    conjuncts(Formula, Facts),
    must_be_facts(Facts, "adopt"),
    declare_goal(B, G, Facts),
    B:'$ga_limits'(Max, _),
    (   Facts == []
    ->  Result = believed,
        Seeded = false
    ;   (   ( Seed == none ; facts_only(Facts, B) )
        ->  Seeded = false
        ;   set_random(seed(Seed)),
            Seeded = true
        ),
        catch(bounded_believed(Facts, B, Max, Believed), E, true),
        (   var(E)
        ->  true
        ;   goal_check_message(E, Max, Message),
            Believed = unchecked(Message)
        ),
        (   Believed == true
        ->  Result = believed
        ;   add_unless_there(B, G, Facts, Result0),
            (   Believed = unchecked(_), Result0 == adopted -> Result = Believed
            ;   Result = Result0
            )
        )
    ).

%   facts_only(+Facts, +B): each of Facts is looked up among facts of B (a dynamic
%   predicate without rules), so checking them runs no code of the agent's.
facts_only(Facts, B) :-
    forall(member(Fact, Facts),
           ( predicate_property(B:Fact, dynamic),
             predicate_property(B:Fact, number_of_rules(0)) )).

bounded_believed(Facts, B, Max, Believed) :-
    (   call_with_inference_limit(\+ \+ all_believed(Facts, B), Max, Outcome)
    ->  (   Outcome == inference_limit_exceeded
        ->  throw(inference_limit_exceeded)
        ;   Believed = true
        )
    ;   Believed = false
    ).

%   goal_check_message(+E, +Max, -Message): what checking a goal met (Max: the agent's
%   --max-inferences); an abort or a Python exception passes on.
goal_check_message(E, _, _) :-
    passes_on(E, none), !,
    throw(E).
goal_check_message(inference_limit_exceeded, Max, Message) :- !,
    format(string(Message), "ran more than ~D inferences (--max-inferences)", [Max]).
goal_check_message(ga_limit(time(T)), _, Message) :- !,
    format(string(Message), "ran longer than ~w s (--max-query-seconds)", [T]).
goal_check_message(E, _, Message) :-
    error_message(E, Message0),
    format(string(Message), "raised an error: ~w", [Message0]).

must_be_facts([], _).
must_be_facts([Fact|Facts], Action) :-
    must_be_fact(Fact, Action),
    must_be_facts(Facts, Action).

all_believed([], _).
all_believed([Fact|Facts], B) :-
    B:Fact,
    all_believed(Facts, B).

%   add_goal(+B, +G, +Base, +Facts, +Key): a new goal in goal base Base: '$goal'(Base, Id,
%   Key), Key its facts sorted (an equal goal is found at once), and '$gf'(Id, Fact,
%   WatchKey) per fact (see watch/1).
add_goal(B, G, Base, Facts, Key) :-
    nb_getval('$ga_goal_id', Id),           % (flag/3 takes a mutex: dearer)
    Next is Id + 1,
    nb_setval('$ga_goal_id', Next),
    add_goal_facts(Facts, Id, B, G),
    assertz(G:'$goal'(Base, Id, Key)),
    watch(G).

add_goal_facts([], _, _, _).
add_goal_facts([Fact|Facts], Id, B, G) :-
    watch_key(B, Fact, WatchKey),
    assertz(G:'$gf'(Id, Fact, WatchKey)),
    add_goal_facts(Facts, Id, B, G).

%   watch(+G): the global variable named after G gets what G's goals watch (see
%   may_achieve/2): any, or the sorted list of the plain belief predicates of their facts
%   ([] when there are none). A rule inserted as a belief makes it any for good.
watch(G) :-
    findall(Key, G:'$gf'(_, _, Key), Keys),
    sort(Keys, Set),
    (   ( memberchk(any, Set) ; G:'$rule_inserted' )
    ->  Watched = any
    ;   Watched = Set
    ),
    nb_setval(G, Watched).

%   watch_key(+B, +Fact, -Key): what can make the goal fact Fact believed. Name/Arity for
%   a plain belief (its predicate has only facts in B and no knowledge clauses): only
%   adding such a fact; any: anything (knowledge, belief rules, built-ins, other modules).
%   Kept per predicate in '$ga_wk'/2 (a rule inserted later is seen by watch/1).
watch_key(B, Fact, Key) :-
    functor(Fact, Name, Arity),
    (   B:'$ga_wk'(Name/Arity, Known)       % known once: dynamic or not, knowledge or not
    ->  Key = Known
    ;   plain_key(B, Name, Arity, Key),
        assertz(B:'$ga_wk'(Name/Arity, Key))
    ).

plain_key(B, Name, Arity, Key) :-
    functor(Head, Name, Arity),
    (   \+ B:'$kpred'(Name/Arity),
        (   predicate_property(B:Head, dynamic)
        ->  \+ ( clause(B:Head, Body), Body \== true ),
            \+ predicate_property(B:Head, imported_from(_))
        ;   \+ predicate_property(B:Head, defined)
        )
    ->  Key = Name/Arity
    ;   Key = any
    ).

goal_facts(G, Id, Facts) :-
    findall(F, G:'$gf'(Id, F, _), Facts).

remove_goal(G, Id, Facts) :-
    goal_facts(G, Id, Facts),
    retractall(G:'$gf'(Id, _, _)),
    retractall(G:'$goal'(_, Id, _)),
    watch(G).

%!  drop(+B, +G, +Formula, -Removed) is det.
%   Removes every goal of the top goal base from which Formula follows.

drop(B, G, Formula0, Removed) :-
    (   callable(Formula0),
        functor(Formula0, Name, Arity),
        G:'$fwd'(Name/Arity)                % a goal predicate: declared already, the
    ->  Formula = Formula0                  % agent's own
    ;   declare(B, G, [Formula0], Declared),
        (   Declared = error(_, Message) -> throw(ga_error(Message)) ; true ),
        ga_confine:prepare_query(Formula0, B, Formula)
    ),
    G:'$top'(Base),
    findall(Id, entails(G, Base, Formula, Id), Ids),
    maplist(remove_goal(G), Ids, Removed).

%   entails(+G, +Base, +Formula, -Id): Formula follows from goal Id of Base (and knowledge).
entails(G, Base, Formula, Id) :-
    G:'$goal'(Base, Id, _),
    \+ \+ ( b_setval('$ga_g', Id), G:Formula ).

%!  blind_commitment(+B, +G, -Removed) is det.
%   Removes every goal (all goal bases) whose facts are all believed.

%   A goal whose check passes a limit or raises an error is kept, and told as a problem
%   (see achieved_checked/3); each goal is checked once (ids grow in clause order).
blind_commitment(B, G, Removed) :-
    (   G:'$goal'(_, Id, _),
        achieved_checked(B, G, Id)
    ->  findall(Id1, ( G:'$goal'(_, Id1, _), Id1 > Id, achieved_checked(B, G, Id1) ), Ids),
        maplist(remove_goal(G), [Id|Ids], Removed),
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

%!  check_goals_bounded(+B, +G, -Removed, -Unchecked) is det.
%   check_goals/3 for Python (the end of a cycle), within the agent's --max-inferences;
%   Unchecked lists Facts-Message for each goal kept because its check passed a limit or
%   raised an error.
check_goals_bounded(B, G, Removed, Unchecked) :-
    B:'$ga_limits'(Max, _),
    b_setval('$ga_max_inferences', Max),
    nb_setval('$ga_unchecked', []),
    call_cleanup(call_with_inference_limit(check_goals(B, G, Removed0), Max, Outcome),
                 ( nb_getval('$ga_unchecked', Unchecked0),
                   nb_setval('$ga_unchecked', none) )),
    (   Outcome == inference_limit_exceeded  % (each goal's check catches its own)
    ->  Removed = []
    ;   Removed = Removed0
    ),
    reverse(Unchecked0, Unchecked).

achieved(B, G, Id) :-
    \+ ( G:'$gf'(Id, Fact, _), \+ B:Fact ).

%   achieved_checked(+B, +G, +Id): goal Id is achieved; a check that passes a limit or
%   raises an error fails (the goal is kept), told as the running rule's problem and noted
%   for check_goals_bounded/4 (in a global variable, which backtracking does not undo).
achieved_checked(B, G, Id) :-
    catch(achieved(B, G, Id), E, ( unchecked_goal(E, G, Id), fail )).

unchecked_goal(E, G, Id) :-
    (   nb_current('$ga_max_inferences', Max) -> true ; Max = 0 ),
    goal_check_message(E, Max, Message),
    goal_facts(G, Id, Facts),
    (   nb_current('$ga_rule', Rule), integer(Rule) -> true ; Rule = none ),
    problem(goal_check(Rule, Facts, Message)),
    (   nb_getval('$ga_unchecked', Seen), Seen \== none
    ->  nb_setval('$ga_unchecked', [Facts-Message|Seen])
    ;   true
    ).

%!  goals(+G, -Goals) is det.
goals(G, Goals) :-
    G:'$top'(Base),
    findall(Facts, ( G:'$goal'(Base, Id, _), goal_facts(G, Id, Facts) ), Goals).

%!  goal_count(+G, -N) is det.
%   How many goals the top goal base holds (without copying them out: a summary needs only
%   the number, and a goal too deeply nested to convert must not stop the report).
goal_count(G, N) :-
    G:'$top'(Base),
    aggregate_all(count, G:'$goal'(Base, _, _), N).

%!  push(+B, +G, +Goals) is det.
push(B, G, Goals) :-
    maplist(conjuncts_or_list, Goals, FactLists),
    forall(( member(Facts, FactLists), member(F, Facts) ), must_be_fact(F, "goal")),
    forall(member(Facts, FactLists), declare_goal(B, G, Facts)),
    retract(G:'$top'(Base0)),
    Base is Base0 + 1,
    assertz(G:'$top'(Base)),
    forall(member(Facts, FactLists), ( msort(Facts, Key), add_goal(B, G, Base, Facts, Key) )),
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
    ->  findall(Id, G:'$goal'(Base, Id, _), Ids),
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

%!  receive(+B, +Messages, +Replace) is det.
%   B believes each of the received/2 facts Messages (once); Replace == true: instead of the
%   received/2 facts it had (GOAL 6+'s message base holds one cycle's mail).
receive(B, Messages, Replace) :-
    (   Replace == true -> retractall(B:received(_, _)) ; true ),
    forall(member(M, Messages), add_once(B, M, _)),
    recheck(B).

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
