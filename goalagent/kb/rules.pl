		 /*******************************
		 *       RULE INTERPRETER       *
		 *******************************/

/*  The one rule interpreter: every rule of every agent runs here, whether or not someone
    watches. Each rule is compiled once into clauses of module ga_rules (shared by all
    agents that read it alike, see compile_rule/6) that do what GOAL says a rule does, with
    the actions of its combo written out; each list of rules (a module, a nested block)
    into a pass (compile_pass/4); run/5 runs the passes of a cycle in one call. The
    clauses call the action predicates below, so each action's semantics is written once.

    What needs Python -- the environment, print/log output, messages, module calls, the
    agent's random order of rules, warnings -- is asked for through the foreign predicate
    '$ga_py'(+Request, -Reply) (goalagent/kb/interpreter.py answers it). When the agent has
    listeners, every step is also told to Python as an event (tell/1): the rules tried with
    their instantiations, firings, refused actions, belief and goal changes. The same code
    runs either way; listening only adds the telling.

    Ctx = ctx(B, G, Env, Listen, Journal, Pending): the agent's belief and goal modules,
    whether it has an environment (its user actions go there unless @int), whether it has
    listeners, the head of the call's journal, and whether goals may need the full check
    after the next update (see check_code/4). The journal: per completed firing f(RuleId, Bound, Done, Terms)
    in order, Bound being v(V1, ..., Vn), the values of the bindings the rule's actions see
    (as listed when it was compiled; a compound, which the journal's record copies in
    fewer cells than a list), Done the number of actions performed, Terms the closed forms
    of the user actions whose arguments only their precondition binds. Python reads the
    journal only when someone asks what fired.
*/

%!  run(+Call, -Outcome, -Journal) is det.
%   Call = r(B, G, Env, Listen, CountLast, Passes): runs Passes, a list of p(Pass, Given)
%   (a compiled pass and the values of its given variables), in turn for the agent whose
%   belief and goal modules are B and G; a module that performs exit-module ends only its own pass. Env:
%   true when the agent has an environment; Listen: true when it has listeners;
%   CountLast: true to count the actions of the last pass. Outcome, one integer (one
%   number crosses to Python faster than several terms): Total << 32 + LastActions << 2 +
%   Exited << 1 + Recheck, Total being the actions performed, LastActions those of the
%   last pass (0 unless asked), Exited 1 when the last pass performed exit-module,
%   Recheck 1 when goals still need a full blind commitment check.
%   The agent's limits (B:'$ga_limits'(MaxInferences, MaxBeliefs), see guard.pl): the
%   call may make at most MaxInferences inferences (one call_with_inference_limit/3 per
%   call: per rule it cost a fifth of a cycle) -- the rule running when they are used up is
%   not applicable, with a warning (see limit_error/2), and the rest of the call is bounded
%   by the time limit only (the watchdog's, goalagent/kb/watchdog.py) --, and the agent may
%   hold at most MaxBeliefs facts after the call (else ga_limit(beliefs(N, Max)) is thrown).

run(r(B, G, Env, Listen, CountLast, Passes), Outcome, Journal) :-
    (   Listen == true -> b_setval('$ga_listen', true) ; true ),
    B:'$ga_limits'(MaxInferences, MaxBeliefs),
    b_setval('$ga_max_inferences', MaxInferences),
    nb_linkval('$ga_aborted_rule', none),     % (an atom: nothing to copy)
    nb_getval(B, Pending),
    Ctx = ctx(B, G, Env, Listen, Journal, Pending),
    call_with_inference_limit(run_passes(Passes, Ctx, Journal, Status, Last), MaxInferences,
                              Result),
    (   Result == inference_limit_exceeded   % between rules: the call ends there
    ->  throw(ga_limit(inferences(MaxInferences)))
    ;   true
    ),
    ga_guard:belief_bound(B, MaxBeliefs),
    journal_actions(Journal, 0, Total),
    (   CountLast == true -> journal_actions(Last, 0, LastActions) ; LastActions = 0 ),
    (   nb_getval(B, true) -> Recheck = 1 ; Recheck = 0 ),
    (   Status == exit -> Exited = 2 ; Exited = 0 ),
    Outcome is Total << 32 + LastActions << 2 + Exited + Recheck.

%   run_passes(+Passes, +Ctx, ?J0, -Status, -Last): Last is the last pass's part of the
%   journal.
run_passes([p(Pass, Given)|Passes], Ctx, J0, Status, Last) :-
    call(ga_rules:Pass, Ctx, Given, J0, J1, Status0),
    (   Passes == []
    ->  J1 = [],
        Last = J0,
        Status = Status0
    ;   run_passes(Passes, Ctx, J1, Status, Last)
    ).

%!  define_plan(+B, +Name, +Call) is det.
%   B:Name(Outcome, Journal) runs Call (see run/3): a cycle's plan, the same every cycle,
%   called by its predicate with only its two outputs (no input to put each cycle).
define_plan(B, Name, Call) :-
    Head =.. [Name, Outcome, Journal],
    assertz(B:(Head :- ga_kb:run(Call, Outcome, Journal))).

journal_actions([], N, N).
journal_actions([f(_, _, Done, _)|J], N0, N) :-
    N1 is N0 + Done,
    journal_actions(J, N1, N).

		 /*******************************
		 *            PASSES            *
		 *******************************/

%!  compile_pass(+Name, +Stop, +Random, +Rules) is det.
%   Asserts ga_rules:Name(Ctx, Given, J0, J, Status) applying the compiled rules Rules
%   (names, see compile_rule/6; all take the same given variables) in order, or in an
%   order Python draws from the agent's random stream (Random = true), stopping after the
%   first that fires when Stop = true. Status: fired, none, or exit (exit-module, which
%   ends the pass). In order, the pass is one clause calling the rules in turn.

compile_pass(Name, Stop, Random, Rules) :-
    Head =.. [Name, Ctx, Given, J0, J, Status],
    (   Random == true
    ->  Body = ga_kb:apply_shuffled(Stop, Rules, Ctx, Given, J0, J, Status)
    ;   Stop == true
    ->  pass_until_fired(Rules, Ctx, Given, J0, J, Status, Body)
    ;   pass_all(Rules, Ctx, Given, J0, J, Status, [], Body)
    ),
    define_static([Head :- Body], [Name/5]).

%   define_static(+Clauses, +Predicates): Clauses in ga_rules, their arithmetic (the
%   interpreter's own integers: actions done) compiled inline, and then Predicates made
%   static (compile_predicates/1): they never change, and a call of a static predicate
%   costs less than one of a dynamic one.
define_static(Clauses, Predicates) :-
    ga_sizes:with_optimise(ga_kb:forall(member(Clause, Clauses),
                                          assertz(ga_rules:Clause))),
    forall(member(Predicate, Predicates), compile_predicates([ga_rules:Predicate])).

pass_until_fired([], _, _, J0, J, Status, (J = J0, Status = none)).
pass_until_fired([Rule|Rules], Ctx, Given, J0, J, Status,
                 (Call, ( Status1 == none -> Rest ; J = J1, Status = Status1 ))) :-
    Call =.. [Rule, Ctx, Given, J0, J1, Status1],
    pass_until_fired(Rules, Ctx, Given, J1, J, Status, Rest).

pass_all([], _, _, J0, J, Status, Statuses,
         (J = J0, ( Fired -> Status = fired ; Status = none ))) :-
    any_fired(Statuses, Fired).
pass_all([Rule|Rules], Ctx, Given, J0, J, Status, Statuses,
         (Call, ( Status1 == exit -> J = J1, Status = exit ; Rest ))) :-
    Call =.. [Rule, Ctx, Given, J0, J1, Status1],
    pass_all(Rules, Ctx, Given, J1, J, Status, [Status1|Statuses], Rest).

%   any_fired(+Statuses, -Test): a goal true when one of the rules' statuses is fired,
%   written out (the pass runs every cycle: no list built, no memberchk/2 call).
any_fired([], fail).
any_fired([Status], Status == fired) :- !.
any_fired([Status|Statuses], ( Status == fired ; Test )) :-
    any_fired(Statuses, Test).

apply_shuffled(Stop, Rules0, Ctx, Given, J0, J, Status) :-
    (   Rules0 = [_, _|_]
    ->  length(Rules0, N),
        '$ga_py'(shuffle(N), Order),
        maplist(nth0_of(Rules0), Order, Rules)
    ;   Rules = Rules0
    ),
    apply_rules(Rules, Stop, Ctx, Given, J0, J, none, Status).

nth0_of(List, Index, Element) :-
    nth0(Index, List, Element).

apply_rules([], _, _, _, J, J, Status, Status).
apply_rules([Rule|Rules], Stop, Ctx, Given, J0, J, Status0, Status) :-
    call(ga_rules:Rule, Ctx, Given, J0, J1, Status1),
    (   Status1 == exit
    ->  J = J1,
        Status = exit
    ;   Status1 == fired
    ->  (   Stop == true
        ->  J = J1,
            Status = fired
        ;   apply_rules(Rules, Stop, Ctx, Given, J1, J, fired, Status)
        )
    ;   apply_rules(Rules, Stop, Ctx, Given, J1, J, Status0, Status)
    ).

		 /*******************************
		 *            LIMITS            *
		 *******************************/

%   A limit met in a rule's condition or action (inference_limit_exceeded from run/3's
%   call_with_inference_limit/3, ga_limit(time(T)) from the watchdog) makes the rule not
%   applicable, with a warning naming it; an abort ('$aborted': Ctrl-C, SIGTERM, a
%   query that outlived its time limit twice) and a Python exception on its way out pass
%   on, whatever catches them on the way (the rule an abort met is noted for the message).

%   condition_error(+E, +Id): an error in the condition of rule Id.
condition_error(E, Id) :-
    (   limit_error(E, Limit)
    ->  problem(limit(Id, Limit))
    ;   passes_on(E, Id)
    ->  throw(E)
    ;   problem(condition(Id, E))
    ).

limit_error(E, _) :- var(E), !, fail.
limit_error(inference_limit_exceeded, inferences(Max)) :-
    b_getval('$ga_max_inferences', Max).
limit_error(ga_limit(Limit), Limit) :-
    Limit \= memory(_, _).                   % (stops the agent: see passes_on/2)

%   passes_on(+E, +Id): E ends more than the rule Id (noting Id for an abort's message);
%   an agent over its memory (memory.pl) is stopped.
passes_on(E, _) :- var(E), !, fail.
passes_on('$ga_python', _).
passes_on(ga_limit(memory(_, _)), _).
passes_on('$aborted', Id) :-
    (   nb_current('$ga_aborted_rule', none) -> nb_setval('$ga_aborted_rule', Id) ; true ).

%   caught(+E, +Id): in the recovery of catch/3 for rule Id: catch/3 throws '$aborted' again
%   right after it, so the rule is noted (and the condition's findall bag freed) here.
caught(E, Id) :-
    (   E == '$aborted'
    ->  '$destroy_findall_bag',
        passes_on(E, Id)
    ;   true
    ).

%   stops_action(+E): E ends the action it is raised in (handled by action_error/3).
stops_action(E) :- limit_error(E, _), !.
stops_action(E) :- passes_on(E, none).

		 /*******************************
		 *            RULES             *
		 *******************************/

%!  compile_rule(+B, +Name, +Id, +Kind, +Condition, +Text) is det.
%   Text is '$rule'(Given, Values, Body), read with B's operators so that its parts share
%   variables: Given, the list of the variables the rule is given (a module's parameters,
%   an enclosing rule's bindings); Values, the list of the bindings its body sees (see the
%   journal); Body, actions(Actions) or rules(Pass, InnerGiven) for a nested block.
%   Condition = c(CondName, CondNames): the condition compiled in every agent as
%   CondName/N (see compile/5) and its variables' names. Kind: if, forall or
%   listall(Collected, List) (the names of the variables collected and of the list).
%
%   Actions: insert(F), delete(F), adopt(F), drop(F); do(Action, Open) for a user action
%   (Open = true: record its closed form in the journal); print(T), log(T);
%   send(Once, Mood, Receiver, Content); module(Index, Args) (a call of the program's
%   module Index); exit_module; sleep(Millis) (GOAL 6+, performed without waiting);
%   goal7(Name, Args): GOAL 7's timers and channels, done in Python.
%
%   Asserts Name(Ctx, Given, J0, J, Status), which computes every instantiation of
%   the condition first, in the state the rule starts in (GOAL's semantics; a Prolog error
%   in the condition is a warning and the rule is not applicable), and puts an if rule's
%   in an order drawn from the agent's random stream (GOAL picks an applicable
%   instantiation at random); and Name_fire, which tries them: an if rule fires with the
%   first one whose attempt succeeds, a forall rule with every one, a listall rule once
%   (its list holds one entry per distinct answer, see listall_entry/2). An attempt performs the combo
%   with one instantiation: its actions in order until one is not enabled (an action that raises
%   an error is not enabled: a warning) or exit-module, blind commitment after each; the
%   attempt fails when its first action is not enabled (or no rule of its block fired).

compile_rule(B, Name, Id, Kind, c(CondName, CondNames), Text) :-
    read_text(Text, B, '$rule'(Given, Values, Body), Bindings),
    maplist(named_var(Bindings), CondNames, CondVars),
    Cond =.. [CondName|CondVars],
    atom_concat(Name, '_fire', Fire),
    rule_clause(Kind, Bindings, CondNames, CondVars, Id, Cond, Values, Given, Name, Fire,
                Clause),
    attempt_clause(Body, B, Id, Values, Attempt),
    fire_clauses(Kind, Fire, Attempt, FireClauses),
    last(FireClauses, (FireHead :- _)),
    functor(FireHead, Fire, FireArity),
    define_static([Clause|FireClauses], [Name/5, Fire/FireArity]).

%   named_var(+Bindings, +Name, -Var): the variable called Name in the rule text (a fresh
%   one when the text does not name it, e.g. a condition variable the body never uses).
named_var(Bindings, Name, Var) :-
    (   memberchk(Name=Var0, Bindings)
    ->  Var = Var0
    ;   true
    ).

rule_clause(listall(Collected, ListName), Bindings, CondNames, CondVars, Id, Cond, Values,
            Given, Name, Fire, (Head :- Body)) :- !,
    maplist(named_var(Bindings, CondNames, CondVars), Collected, CollectedVars),
    listall_entry(CollectedVars, Entry),
    named_var(Bindings, ListName, List),
    Head =.. [Name, Ctx, Given, J0, J, Status],
    (   Entry == '$ga_none'
    ->  Collect = ( List = [], Ok = true )
    ;   instances_code(Entry, B:Cond, Id, Entries, Ok, Collect0),
        Collect = ( Collect0, list_to_set(Entries, List) )
    ),
    Body = ( Ctx = ctx(B, _, _, Listen, _, _),
             b_setval('$ga_rule', Id),
             Collect,
             ( Ok == true -> Instances = [Values] ; Instances = [] ),
             ( Listen == true -> ga_kb:tell(tried(Id, Instances)) ; true ),
             FireCall ),
    FireCall =.. [Fire, Instances, Ctx, J0, J, Status].
rule_clause(Kind, _, _, _, Id, Cond, Values, Given, Name, Fire, (Head :- Body)) :-
    Head =.. [Name, Ctx, Given, J0, J, Status],
    instances_code(Values, B:Cond, Id, Instances0, _, Collect),
    (   Kind == if                          % GOAL's random choice of an instantiation
    ->  Order = ( Instances0 = [_, _|_] -> ga_kb:shuffled(Instances0, Instances)
                ; Instances = Instances0 )
    ;   Order = true,
        Instances = Instances0
    ),
    Body = ( Ctx = ctx(B, _, _, Listen, _, _),
             b_setval('$ga_rule', Id),
             Collect,
             Order,
             ( Listen == true -> ga_kb:tell(tried(Id, Instances)) ; true ),
             FireCall ),
    (   Kind == forall
    ->  FireCall =.. [Fire, Instances, Ctx, J0, J, none, Status]
    ;   FireCall =.. [Fire, Instances, Ctx, J0, J, Status]
    ).

%   named_var(+Bindings, +CondNames, +CondVars, +Name, -Var): the condition's variable
%   called Name, else the rule text's (see named_var/3).
named_var(Bindings, CondNames, CondVars, Name, Var) :-
    (   nth0(I, CondNames, Name)
    ->  nth0(I, CondVars, Var)
    ;   named_var(Bindings, Name, Var)
    ).

%   listall_entry(+Vars, -Entry): what one answer adds to a listall rule's list (GOAL's
%   ListallDoRule): the value of the one variable, the list of the values of several, or
%   nothing ('$ga_none') when the condition has no free variable.
listall_entry([], '$ga_none') :- !.
listall_entry([Var], Var) :- !.
listall_entry(Vars, Vars).

%   shuffled(+List, -Shuffled): List in an order drawn from the agent's random stream.
shuffled(List, Shuffled) :-
    length(List, N),
    '$ga_py'(shuffle(N), Order),
    maplist(nth0_of(List), Order, Shuffled).

%   instances_code(+Template, +Goal, +Id, -List, -Ok, -Code): Code collects Template for
%   every solution of Goal into List as findall/3 does; a Prolog error in Goal is told as
%   a problem of rule Id, and List = [] and Ok = false then (else Ok = true). This is
%   findall/3's own loop (boot/bags.pl of SWI-Prolog 9) with one catch/3 instead of
%   findall's setup_call_cleanup/3 inside our catch/3, which cost a quarter of a rule's
%   overhead; the bag is freed on both ways out.
instances_code(Template, Goal, Id, List, Ok,
               ( '$new_findall_bag',
                 catch(ga_kb:collect(Template, Goal, List0), E, ga_kb:caught(E, Id)),
                 '$destroy_findall_bag',
                 (   var(E)
                 ->  List = List0, Ok = true
                 ;   ga_kb:condition_error(E, Id), List = [], Ok = false
                 ) )).

%   collect(+Template, +Goal, -List): the solutions into the current findall bag.
collect(Template, Goal, List) :-
    (   call(Goal),
        '$add_findall_bag'(Template),
        fail
    ;   '$collect_findall_bag'(List, [])
    ).

%   fire_clauses(+Kind, +Fire, +Attempt, -Clauses): Fire over the instantiations, each
%   attempt (Attempt = (Head :- Body), see attempt_clause/5) written out in the clause.
fire_clauses(forall, Fire, (AttemptHead :- Try), [Last, Next]) :- !,
    AttemptHead =.. [_, Values, Ctx, J0, J1, Status1],
    Last =.. [Fire, [], _, J, J, Status, Status],
    Head =.. [Fire, [Values|Instances], Ctx, J0, J, Status0, Status],
    Each =.. [Fire, Instances, Ctx, J1, J, fired, Status],
    Skip =.. [Fire, Instances, Ctx, J0, J, Status0, Status],
    Next = (Head :- ( Try -> ( Status1 == exit -> J = J1, Status = exit ; Each ) ; Skip )).
fire_clauses(_, Fire, (AttemptHead :- Try), [Last, Next]) :-
    AttemptHead =.. [_, Values, Ctx, J0, J1, Status1],
    Last =.. [Fire, [], _, J, J, none],
    Head =.. [Fire, [Values|Instances], Ctx, J0, J, Status],
    Skip =.. [Fire, Instances, Ctx, J0, J, Status],
    Next = (Head :- ( Try -> J = J1, Status = Status1 ; Skip )).

%   attempt_clause(+Body, +CB, +Id, +Values, -Clause): attempt(Values, Ctx, J0, J, Status)
%   :- the attempt (written out in the fire clauses); CB: the module of the agent whose
%   program is being compiled (which of its predicates are dynamic).
attempt_clause(rules(Pass, InnerGiven), _, Id, Values, (Head :- Body)) :- !,
    Head = attempt(Values, Ctx, J0, J, Status),
    Inner =.. [Pass, Ctx, InnerGiven, J0, J1, Status],
    Bound =.. [v|Values],
    Body = ( Inner,
             (   Status == fired
             ->  J1 = [f(Id, Bound, 0, [])|J],
                 ( arg(4, Ctx, true) -> ga_kb:tell(fired(Id, Values, 0, [])) ; true )
             ;   Status == exit
             ->  J = J1
             ) ).
attempt_clause(actions(Actions), CB, Id, Values, (Head :- Body)) :-
    Head = attempt(Values, Ctx, J0, J, Status),
    Vars = v(Ctx, B, G, Listen, CB),
    perform_code(Actions, 0, f(Id, Values), Vars, Done, Terms, Status, Perform),
    Bound =.. [v|Values],
    Body = ( Ctx = ctx(B, G, _, Listen, _, _),
             Perform,
             Done > 0,
             J0 = [f(Id, Bound, Done, Terms)|J],
             ( Listen == true -> ga_kb:tell(fired(Id, Values, Done, Terms)) ; true ) ).

%   perform_code(+Actions, +K, +Firing, +Vars, -Done, -Terms, -Status, -Code): the code
%   performing Actions from the K-th on.
perform_code([], K, _, _, Done, Terms, Status, (Done = K, Terms = [], Status = fired)).
perform_code([Action|Actions], K, Firing, Vars, Done, Terms, Status, Code) :-
    action_goal(Action, K, Firing, Vars, Goal0, Outcome),
    (   Goal0 = safe(Goal)                  % reports its own problems, never throws
    ->  Call = Goal
    ;   Call = catch(Goal0, E, ga_kb:action_error(E, K, Firing))
    ),
    K1 is K + 1,
    (   Outcome == exit
    ->  Then = ( Done = K1, Terms = [], Status = exit )
    ;   perform_code(Actions, K1, Firing, Vars, Done, Terms1, Status, Rest),
        (   Outcome = term(Term)
        ->  Record = ( Terms = [Term|Terms1] )
        ;   Record = ( Terms = Terms1 )
        ),
        check_code(Action, Outcome, Vars, Check),
        Then = ( Check, Record, Rest )
    ),
    Code = (   Call
           ->  Then
           ;   Done = K, Terms = [], Status = fired
           ).

%   check_code(+Action, +Outcome, +Vars, -Code): what follows Action for the goals that
%   percepts, messages or a new goal base may have achieved: the first action after they
%   came checks every goal (the recheck flag, a global variable named after the belief
%   module, see recheck/1). Only Python sets the flag (between cycles, or in an action that
%   asks Python for something, a module call included), so Ctx's Pending holds it as it
%   was at the call's start and as it is after each such action, and after an update
%   (insert, delete, adopt, drop) one inline test of Pending, no call, says whether to look:
%   most actions pay nothing. A module call runs its own check; after it, Pending is
%   brought up to date.
check_code(_, called, v(Ctx, B, _, _, _), ga_kb:recheck_after_call(Ctx, B)) :- !.
check_code(Action, _, v(Ctx, B, G, _, _), Code) :-
    (   asks_python(Action)
    ->  Code = ( nb_getval(B, true) -> ga_kb:check_goals(B, G, _) ; true )
    ;   Code = ( Ctx = ctx(_, _, _, _, _, Pending),
                 (   Pending == true -> ga_kb:recheck_goals(Ctx, B, G) ; true ) )
    ).

asks_python(do(_, _)).
asks_python(print(_)).
asks_python(log(_)).
asks_python(send(_, _, _, _)).
asks_python(goal7(_, _)).

%   recheck_goals(+Ctx, +B, +G): the full check, the flag and Ctx's Pending cleared
%   (nb_setarg/3: a clear undone by backtracking would only cost one more look).
recheck_goals(Ctx, B, G) :-
    check_goals(B, G, _),
    nb_setarg(6, Ctx, false).

%   recheck_after_call(+Ctx, +B): Ctx's Pending set when a module call left the flag set
%   (not undone by backtracking: the flag is not either).
recheck_after_call(Ctx, B) :-
    (   nb_getval(B, true) -> nb_setarg(6, Ctx, true) ; true ).

%   action_goal(+Action, +K, +Firing, +Vars, -Goal, -Outcome): the goal that performs
%   Action (safe(Goal): one that reports its own problems, so needs no catch/3); Outcome:
%   done, term(T) (the closed action to record), called (a module call: its own blind
%   commitment) or exit. After an action, updates have checked what they
%   changed (update/7 and the like); the first action after new percepts, messages or
%   goal bases checks every goal (the recheck flag, see recheck/1).
action_goal(insert(F), K, Firing, v(_, B, G, Listen, CB), Goal, done) :-
    update_goal(insert, F, K, Firing, B, G, Listen, CB, Goal).
action_goal(delete(F), K, Firing, v(_, B, G, Listen, CB), Goal, done) :-
    update_goal(delete, F, K, Firing, B, G, Listen, CB, Goal).
action_goal(adopt(F), K, Firing, v(_, B, G, Listen, _),
            ga_kb:adopt_action(B, G, Listen, F, K, Firing), done).
action_goal(drop(F), _, _, v(_, B, G, Listen, _), ga_kb:drop_action(B, G, Listen, F), done).
action_goal(do(Action, Open), K, Firing, v(Ctx, _, _, _, _),
            ga_kb:user_action(Action, K, Firing, Ctx, Term), Outcome) :-
    (   Open == true -> Outcome = term(Term) ; Outcome = done ).
action_goal(print(T), _, _, _, ga_kb:output(print, T), done).
action_goal(log(T), _, _, _, ga_kb:output(log, T), done).
action_goal(send(Once, Mood, Receiver, Content), K, Firing, _,
            ga_kb:'$ga_py'(send(Firing, K, Once, Mood, Receiver, Content), true), done).
action_goal(module(Index, Args), K, Firing, v(Ctx, _, _, _, _),
            ga_kb:module_call(Ctx, K, Firing, Index, Args), called).
action_goal(sleep(_), _, _, _, true, done).   % agents take turns: nothing to wait for
action_goal(goal7(Name, Args), _, _, _, ga_kb:'$ga_py'(goal7(Name, Args), _), done).
action_goal(exit_module, _, _, _, true, exit).

%   update_goal(+Mode, +Formula, +K, +Firing, +B, +G, +Listen, +CB, -Goal): insert or
%   delete of a formula whose literals are facts (no variable literal, no control
%   construct, no rule) split at compile time into the facts to delete and to add (see
%   insert_one/7, delete_one/4, update_facts/5); one fact of a predicate dynamic in the
%   program's agent (CB) is safe: it cannot raise an error. Any other formula is split
%   when performed (update/7).
update_goal(Mode, Formula, K, Firing, B, G, Listen, CB, Goal) :-
    catch(split_formula(Formula, Mode, Adds, [], Dels, []), _, fail),
    forall(( member(Fact, Adds) ; member(Fact, Dels) ), known_fact(Fact)),
    !,
    (   Dels == [], Adds = [Fact], dynamic_in(CB, Fact)
    ->  functor(Fact, Name, Arity),
        ground_code(Fact, ga_kb:insert_ground(B, G, Listen, Fact, Name/Arity),
                    ga_kb:insert_one(B, G, Listen, Fact, Name/Arity, K, Firing), Code),
        Goal = safe(Code)
    ;   Adds == [], Dels = [Fact], dynamic_in(CB, Fact)
    ->  ground_code(Fact, ga_kb:delete_ground(B, G, Listen, Fact),
                    ga_kb:delete_one(B, G, Listen, Fact), Code),
        Goal = safe(Code)
    ;   Goal = ga_kb:update_facts(B, G, Listen, Dels, Adds)
    ).
update_goal(Mode, Formula, _, _, B, G, _, _, ga_kb:update(B, G, Mode, Formula, _, _, _)).

%   ground_code(+Fact, +IfGround, +Otherwise, -Code): Code runs IfGround when Fact is
%   ground, else Otherwise (which tests it itself): written as inline atomic/1 tests of
%   Fact's variables (most hold a number or an atom), no call of ground/1.
ground_code(Fact, IfGround, Otherwise, Code) :-
    term_variables(Fact, Vars),
    (   Vars == []
    ->  Code = IfGround
    ;   ga_sizes:type_test(atomic, Vars, Test),
        Code = ( Test -> IfGround ; Otherwise )
    ).

dynamic_in(Module, Fact) :-
    functor(Fact, Name, Arity),
    functor(Head, Name, Arity),
    predicate_property(Module:Head, dynamic),
    \+ predicate_property(Module:Head, imported_from(_)).

known_fact(Fact) :-
    nonvar(Fact),
    fact_like(Fact),
    Fact \= (_ :- _).

		 /*******************************
		 *            ACTIONS           *
		 *******************************/

adopt_action(B, G, Listen, F, K, Firing) :-
    adopt(B, G, F, Result),
    (   Result == adopted
    ->  (   Listen == true -> tell(goal(adopted, F)) ; true )
    ;   (   Listen == true -> tell(refused(Firing, K, Result)) ; true ),
        fail
    ).

drop_action(B, G, Listen, F) :-
    drop(B, G, F, Removed),
    (   Listen == true -> forall(member(Goal, Removed), tell(goal(dropped, Goal))) ; true ).

%   A user action: the first actionspec whose head unifies and whose precondition holds
%   (see declare_actions/2); its precondition's bindings do not flow into the rule. It
%   must then be closed. With an environment (and not @int) Python sends it there; as in
%   GOAL's runtime (RunState.doPerformAction), an action the environment refuses or fails
%   is a warning and still counts as performed: its postcondition follows and the rule's
%   next actions run (an action the environment cannot take at all stops the agent, in
%   Python). A failing postcondition is then a warning (the environment was asked).
%   Otherwise the postcondition alone is the action.
user_action(Action0, K, Firing, ctx(B, G, Env, Listen, _, _), Action) :-
    (   ground(Action0) -> Action = Action0 ; copy_term(Action0, Action) ),
    (   B:'$ga_pre'(Action, Post, _, Internal)
    ->  true
    ;   (   Listen == true -> tell(refused(Firing, K, precondition)) ; true ),
        fail
    ),
    (   ground(Action) -> true ; throw(ga_open(Action)) ),
    (   Internal == false,
        Env == true
    ->  '$ga_py'(act(Firing, K, Action), _),
        catch(update(B, G, insert, Post, _, _, _), E,
              ( stops_action(E) -> throw(E) ; problem(action(Firing, K, E)) ))
    ;   update(B, G, insert, Post, _, _, _)
    ).

%   print/1 and log/1: atoms and strings as they are, other terms as writeq shows them
%   (within ga_sizes:printable/1's bounds).
output(Kind, T) :-
    ga_sizes:printable(T),
    (   ( atom(T) ; string(T) )
    ->  atom_string(T, Text)
    ;   write_text(T, true, Text)
    ),
    Request =.. [Kind, Text],
    '$ga_py'(Request, _).

module_call(Ctx, K, Firing, Index, Args) :-
    journal_position(Ctx, K, Entries, Position),
    '$ga_py'(call(Firing, K, Index, Args, Entries, Position), true).

action_error(E, _, f(Id, _)) :-
    limit_error(E, Limit), !,
    problem(limit(Id, Limit)),
    fail.
action_error(E, _, f(Id, _)) :-
    passes_on(E, Id), !,
    throw(E).                             % an abort or a Python exception
action_error(ga_open(Action), K, Firing) :- !,
    problem(open(Firing, K, Action)),
    fail.
action_error(E, K, Firing) :-
    problem(action(Firing, K, E)),
    fail.

%   journal_position(+Ctx, +K, -Entries, -Position): how many firings the call's journal
%   holds so far, and the place of the current action (the K-th of the firing in
%   progress) in the sequence of actions performed in the call.
journal_position(ctx(_, _, _, _, Journal, _), K, Entries, Position) :-
    journal_position(Journal, 0, Entries, K, Position).

journal_position(J, Entries, Entries, Position, Position) :-
    var(J), !.
journal_position([f(_, _, Done, _)|J], N0, N, P0, P) :-
    N1 is N0 + 1,
    P1 is P0 + Done,
    journal_position(J, N1, N, P1, P).

%!  declare_actions(+B, +Specs) is det.
%   Specs: list of spec(Index, Internal, Text), Text being '$spec'(Action, Pre, Post) for
%   one actionspec (Index: its place in the program). Asserts, in order,
%   B:'$ga_pre'(Action, Post, Index, Internal) :- Pre (Pre compiled as its own clause
%   '$ga_pre_body'/3), so that the first clause whose Action unifies and whose Pre holds
%   gives the action's postcondition. A Prolog error in Pre is
%   a warning and that spec does not apply; so does a Pre that fails, told to listeners.

declare_actions(B, Specs) :-
    forall(member(spec(Index, Internal, Text), Specs),
           ( read_text(Text, B, '$spec'(Action, Pre0, Post), _),
             catch(ga_confine:prepare_query(Pre0, B, Pre), ga_refused(Why),
                   throw(ga_refused_spec(Index, Why))),
             local_cut(Pre, Body),
             assertz(B:('$ga_pre_body'(Index, Action, Post) :- Body)),
             assertz(B:('$ga_pre'(Action, Post, Index, Internal) :-
                           ga_kb:precondition(B:'$ga_pre_body'(Index, Action, Post), Index,
                                              Action))) )).

precondition(Body, Index, Action) :-
    (   catch(Body, E, ( stops_action(E) -> throw(E)
                         ;   problem(precondition(Index, E)), fail ))
    ->  true
    ;   listening,
        tell(precondition_failed(Index, Action)),
        fail
    ).

		 /*******************************
		 *      TELLING PYTHON          *
		 *******************************/

%   listening: the running agent has listeners (run/5 sets it for the call; the rule
%   clauses read it from their Ctx).
listening :-
    b_getval('$ga_listen', true).

%   A warning SWI-Prolog prints while a rule runs (say, a deprecated built-in called from a
%   condition) is told as the rule's problem, with its place, instead of printed bare. Each
%   rule clause sets '$ga_rule' with b_setval/2: a module call's rules run in a query of
%   their own, and when it returns Python discards its frame, which gives the calling rule
%   back its id (undone like a binding).
:- multifile user:message_hook/3.
user:message_hook(_, warning, Lines) :-
    nb_current('$ga_rule', Id),
    integer(Id),
    with_output_to(string(Text0), print_message_lines(current_output, '', Lines)),
    split_string(Text0, "", " \n", [Text]),
    '$ga_py'(problem(warning(Id, Text)), _).

%   tell(+Event): an event for the agent's listeners (only called when listening).
tell(Event) :-
    '$ga_py'(event(Event), _).

%   problem(+Problem): a warning, always told. Errors are turned into messages here.
problem(condition(Id, E)) :- !,
    error_message(E, Message),
    '$ga_py'(problem(condition(Id, Message)), _).
problem(action(Firing0, K, E)) :- !,
    error_message(E, Message),
    ga_sizes:reportable(Firing0, Firing),
    '$ga_py'(problem(action(Firing, K, Message)), _).
problem(precondition(Index, E)) :- !,
    error_message(E, Message),
    '$ga_py'(problem(precondition(Index, Message)), _).
problem(Problem) :-
    '$ga_py'(problem(Problem), _).
