		 /*******************************
		 *       RULE INTERPRETER       *
		 *******************************/

/*  The one rule interpreter: every rule of every agent runs here, whether or not someone
    watches. Python compiles each rule once into a clause of module ga_rules (shared by all
    agents that read the rule alike, see compile_rule/6) and each list of rules (a module,
    a nested block) into a pass (compile_pass/4); run/8 runs module passes in one call.

    What needs Python -- the environment, print/log output, messages, module calls, the
    agent's random order of rules, warnings -- is asked for through the foreign predicate
    '$ga_py'(+Request, -Reply) (goalagent/kb/interpreter.py answers it). When the agent has
    listeners, every step is also told to Python as an event (tell/1): the rules tried with
    their instantiations, firings, refused actions, belief and goal changes. The same code
    runs either way; listening only adds the telling.

    Ctx = ctx(B, G, Env, Journal): the agent's belief and goal modules, whether it has an
    environment (its user actions go there unless @int), and the head of the call's
    journal: per completed firing f(RuleId, Values, Done, Terms) in order, Values being the
    bindings the rule's actions see (as listed when it was compiled), Done the number of
    actions performed, Terms the closed forms of the user actions whose arguments only
    their precondition binds. Python reads the journal only when someone asks what fired.
*/

%!  run(+B, +Env, +Listen, +Passes, -Total, -Last, -Recheck, -Journal) is det.
%   Runs Passes, a list of p(Pass, Given) (a compiled pass and the values of its given
%   variables), in turn; a module that performs exit-module ends only its own pass.
%   Total: the actions performed; Last = s(Status, Actions) for the last pass (Status
%   fired, none or exit); Recheck: true when goals still need a full blind commitment
%   check; Journal: see above.

run(B, Env, Listen, Passes, Total, Last, Recheck, Journal) :-
    B:'$ga_gm'(G),
    b_setval('$ga_listen', Listen),
    Ctx = ctx(B, G, Env, Journal),
    run_passes(Passes, Ctx, Journal, Last),
    journal_actions(Journal, 0, Total),
    nb_getval(B, Recheck).

run_passes([p(Pass, Given)|Passes], Ctx, J0, Last) :-
    call(ga_rules:Pass, Ctx, Given, J0, J1, Status),
    (   Passes == []
    ->  J1 = [],
        journal_actions(J0, 0, Actions),
        Last = s(Status, Actions)
    ;   run_passes(Passes, Ctx, J1, Last)
    ).

journal_actions([], N, N).
journal_actions([f(_, _, Done, _)|J], N0, N) :-
    N1 is N0 + Done,
    journal_actions(J, N1, N).

%!  compile_pass(+Name, +Stop, +Random, +Rules) is det.
%   Asserts ga_rules:Name(Ctx, Given, J0, J, Status) applying the compiled rules Rules
%   (names, see compile_rule/6; all take the same given variables) in order, or in an
%   order Python draws from the agent's random stream (Random = true), stopping after the
%   first that fires when Stop = true. Status: fired, none, or exit (exit-module).

compile_pass(Name, Stop, Random, Rules) :-
    Head =.. [Name, Ctx, Given, J0, J, Status],
    assertz(ga_rules:(Head :- ga_kb:apply_pass(Stop, Random, Rules, Ctx, Given, J0, J,
                                                Status))).

apply_pass(Stop, Random, Rules0, Ctx, Given, J0, J, Status) :-
    (   Random == true,
        Rules0 = [_, _|_]
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

%!  compile_rule(+B, +Name, +Id, +Kind, +Condition, +Text) is det.
%   Text is '$rule'(Given, Values, Body), read with B's operators so that its parts share
%   variables: Given, the list of the variables the rule is given (a module's parameters,
%   an enclosing rule's bindings); Values, the list of the bindings its body sees (see the
%   journal); Body, actions(Actions) or rules(Pass, InnerGiven) for a nested block.
%   Condition = c(CondName, CondNames): the condition compiled in every agent as
%   CondName/N (see compile/5) and its variables' names. Kind: if, forall or
%   listall(Collected, List) (the names of the variable collected and of the list).
%   Asserts ga_rules:Name(Ctx, Given, J0, J, Status) :- apply_rule(...).
%
%   Actions: insert(F), delete(F), adopt(F), drop(F); do(Action, Open) for a user action
%   (Open = true: record its closed form in the journal); print(T), log(T);
%   send(Once, Mood, Receiver, Content); module(Index, Args) (a call of the program's
%   module Index); exit_module; sleep(Millis) (GOAL 6+, performed without waiting).

compile_rule(B, Name, Id, Kind0, c(CondName, CondNames), Text) :-
    read_text(Text, B, '$rule'(Given, Values, Body), Bindings),
    maplist(named_var(Bindings), CondNames, CondVars),
    Cond =.. [CondName|CondVars],
    (   Kind0 = listall(Collected, ListName)
    ->  named_var(Bindings, Collected, CollectedVar, CondNames, CondVars),
        named_var(Bindings, ListName, List),
        Kind = listall(CollectedVar, List)
    ;   Kind = Kind0
    ),
    Head =.. [Name, Ctx, Given, J0, J, Status],
    assertz(ga_rules:(Head :- ga_kb:apply_rule(Kind, Id, Cond, Values, Body, Ctx, J0, J,
                                                Status))).

%   named_var(+Bindings, +Name, -Var): the variable called Name in the rule text (a fresh
%   one when the text does not name it, e.g. a condition variable the body never uses).
named_var(Bindings, Name, Var) :-
    (   memberchk(Name=Var0, Bindings)
    ->  Var = Var0
    ;   true
    ).

named_var(Bindings, Name, Var, CondNames, CondVars) :-
    (   nth0(I, CondNames, Name)
    ->  nth0(I, CondVars, Var)
    ;   named_var(Bindings, Name, Var)
    ).

%!  apply_rule(+Kind, +Id, +Cond, +Values, +Body, +Ctx, ?J0, ?J, -Status) is det.
%   Every instantiation of the condition is computed first, in the state the rule starts
%   in (GOAL's semantics); an if rule (and listall) then fires with the first one whose
%   first action is enabled (or whose nested block fires), a forall rule with every one.
%   A Prolog error in the condition is a warning and the rule is not applicable.

apply_rule(Kind, Id, Cond, Values, Body, Ctx, J0, J, Status) :-
    arg(1, Ctx, B),
    catch(instantiations(Kind, B, Cond, Values, Body, Instances), E,
          ( problem(condition(Id, E)), Instances = [] )),
    (   listening
    ->  pairs_keys(Instances, Tried),
        tell(tried(Id, Tried))
    ;   true
    ),
    (   Kind == forall
    ->  fire_each(Instances, Id, Ctx, J0, J, none, Status)
    ;   fire_first(Instances, Id, Ctx, J0, J, Status)
    ).

%   Each instantiation comes with its own copy of the body (fresh variables for what the
%   condition does not bind). GOAL's random choice among an if rule's instantiations and
%   its one-entry-per-answer listall belong here.
instantiations(listall(Collected, List), B, Cond, Values, Body, [Values-Body]) :- !,
    findall(Collected, B:Cond, List).
instantiations(_, B, Cond, Values, Body, Instances) :-
    findall(Values-Body, B:Cond, Instances).

fire_first([], _, _, J, J, none).
fire_first([Values-Body|Instances], Id, Ctx, J0, J, Status) :-
    (   attempt(Body, Id, Values, Ctx, J0, J1, Status1)
    ->  J = J1,
        Status = Status1
    ;   fire_first(Instances, Id, Ctx, J0, J, Status)
    ).

fire_each([], _, _, J, J, Status, Status).
fire_each([Values-Body|Instances], Id, Ctx, J0, J, Status0, Status) :-
    (   attempt(Body, Id, Values, Ctx, J0, J1, Status1)
    ->  (   Status1 == exit
        ->  J = J1,
            Status = exit
        ;   fire_each(Instances, Id, Ctx, J1, J, fired, Status)
        )
    ;   fire_each(Instances, Id, Ctx, J0, J, Status0, Status)
    ).

%   attempt(+Body, +Id, +Values, +Ctx, ?J0, ?J, -Status): the rule fires with this
%   instantiation (Status fired or exit) or the attempt fails: its first action is not
%   enabled, or no rule of its nested block fired. A failed attempt changed nothing.
attempt(actions(Actions), Id, Values, Ctx, J0, J, Status) :-
    perform(Actions, 0, f(Id, Values), Ctx, Done, Terms, Status),
    Done > 0,
    J0 = [f(Id, Values, Done, Terms)|J],
    (   listening
    ->  tell(fired(Id, Values, Done, Terms))
    ;   true
    ).
attempt(rules(Pass, Given), Id, Values, Ctx, J0, J, Status) :-
    call(ga_rules:Pass, Ctx, Given, J0, J1, Status),
    (   Status == fired
    ->  J1 = [f(Id, Values, 0, [])|J],
        (   listening
        ->  tell(fired(Id, Values, 0, []))
        ;   true
        )
    ;   Status == exit
    ->  J = J1
    ).

%   perform(+Actions, +K, +Firing, +Ctx, -Done, -Terms, -Status): the actions in order
%   from the K-th until one is not enabled (an action that raises an error is not
%   enabled: a warning) or exit-module; blind commitment after each (a module call does
%   its own). Done: how many were performed.
perform([], Done, _, _, Done, [], fired).
perform([Action|Actions], K, Firing, Ctx, Done, Terms, Status) :-
    (   catch(action(Action, K, Firing, Ctx, Outcome), E, action_error(E, K, Firing))
    ->  K1 is K + 1,
        (   Outcome == exit
        ->  Done = K1, Terms = [], Status = exit
        ;   Outcome == called
        ->  perform(Actions, K1, Firing, Ctx, Done, Terms, Status)
        ;   Outcome = term(Term)
        ->  Terms = [Term|Terms1],
            after_action(Ctx),
            perform(Actions, K1, Firing, Ctx, Done, Terms1, Status)
        ;   after_action(Ctx),
            perform(Actions, K1, Firing, Ctx, Done, Terms, Status)
        )
    ;   Done = K, Terms = [], Status = fired
    ).

action(insert(F), _, _, ctx(B, G, _, _), done) :-
    update(B, G, insert, F, _, _, _).
action(delete(F), _, _, ctx(B, G, _, _), done) :-
    update(B, G, delete, F, _, _, _).
action(adopt(F), K, Firing, ctx(B, G, _, _), done) :-
    adopt(B, G, F, Result),
    (   Result == adopted
    ->  (   listening -> tell(goal(adopted, F)) ; true )
    ;   (   listening -> tell(refused(Firing, K, Result)) ; true ),
        fail
    ).
action(drop(F), _, _, ctx(B, G, _, _), done) :-
    drop(B, G, F, Removed),
    (   listening -> forall(member(Goal, Removed), tell(goal(dropped, Goal))) ; true ).
action(do(Action, Open), K, Firing, Ctx, Outcome) :-
    user_action(Action, K, Firing, Ctx, Term),
    (   Open == true -> Outcome = term(Term) ; Outcome = done ).
action(print(T), _, _, _, done) :-
    plain_text(T, Text),
    '$ga_py'(print(Text), _).
action(log(T), _, _, _, done) :-
    plain_text(T, Text),
    '$ga_py'(log(Text), _).
action(send(Once, Mood, Receiver, Content), K, Firing, _, done) :-
    '$ga_py'(send(Firing, K, Once, Mood, Receiver, Content), true).
action(module(Index, Args), K, Firing, Ctx, called) :-
    journal_position(Ctx, K, Entries, Position),
    '$ga_py'(call(Firing, K, Index, Args, Entries, Position), true).
action(exit_module, _, _, _, exit).
action(sleep(_), _, _, _, done).          % agents take turns: nothing to wait for

%   A user action: the first actionspec whose head unifies and whose precondition holds
%   (see declare_actions/2); its precondition's bindings do not flow into the rule. It
%   must then be closed. With an environment (and not @int) Python sends it there and the
%   postcondition follows only if it was done; a failing postcondition is then a warning
%   (the environment did act). Otherwise the postcondition alone is the action.
user_action(Action0, K, Firing, ctx(B, G, Env, _), Action) :-
    (   ground(Action0) -> Action = Action0 ; copy_term(Action0, Action) ),
    (   B:'$ga_pre'(Action, Post, _, Internal)
    ->  true
    ;   (   listening -> tell(refused(Firing, K, precondition)) ; true ),
        fail
    ),
    (   ground(Action) -> true ; throw(ga_open(Action)) ),
    (   Internal == false,
        Env == true
    ->  '$ga_py'(act(Firing, K, Action), Reply),
        (   Reply == done
        ->  catch(update(B, G, insert, Post, _, _, _), E,
                  problem(action(Firing, K, E)))
        ;   true
        )
    ;   update(B, G, insert, Post, _, _, _)
    ).

%   print/1 and log/1 text: atoms and strings as they are, other terms as writeq shows them.
plain_text(T, Text) :-
    (   ( atom(T) ; string(T) )
    ->  atom_string(T, Text)
    ;   write_text(T, true, Text)
    ).

action_error('$ga_python', _, _) :- !,
    throw('$ga_python').                  % a Python exception on its way out
action_error(ga_open(Action), K, Firing) :- !,
    problem(open(Firing, K, Action)),
    fail.
action_error(E, K, Firing) :-
    problem(action(Firing, K, E)),
    fail.

%   Blind commitment after an action: insert/delete checked what they changed (update/7);
%   the first action after new percepts, messages or goal bases checks every goal.
after_action(ctx(B, G, _, _)) :-
    (   nb_getval(B, true)
    ->  nb_setval(B, false),
        blind_commitment(B, G, _)
    ;   true
    ).

%   journal_position(+Ctx, +K, -Entries, -Position): how many firings the call's journal
%   holds so far, and the place of the current action (the K-th of the firing in
%   progress) in the sequence of actions performed in the call.
journal_position(ctx(_, _, _, Journal), K, Entries, Position) :-
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
%   B:'$ga_pre'(Action, Post, Index, Internal) :- Pre, so that the first clause whose Action
%   unifies and whose Pre holds gives the action's postcondition. A Prolog error in Pre is
%   a warning and that spec does not apply; so does a Pre that fails, told to listeners.

declare_actions(B, Specs) :-
    forall(member(spec(Index, Internal, Text), Specs),
           ( read_text(Text, B, '$spec'(Action, Pre, Post), _),
             local_cut(Pre, Body),
             assertz(B:('$ga_pre'(Action, Post, Index, Internal) :-
                           ga_kb:precondition(B:Body, Index, Action))) )).

precondition(Body, Index, Action) :-
    (   catch(Body, E, ( problem(precondition(Index, E)), fail ))
    ->  true
    ;   listening,
        tell(precondition_failed(Index, Action)),
        fail
    ).

		 /*******************************
		 *      TELLING PYTHON          *
		 *******************************/

%   listening: the running agent has listeners (run/8 sets it for the call).
listening :-
    b_getval('$ga_listen', true).

%   tell(+Event): an event for the agent's listeners (only called when listening).
tell(Event) :-
    '$ga_py'(event(Event), _).

%   problem(+Problem): a warning, always told. Errors are turned into messages here.
problem(condition(Id, E)) :- !,
    error_message(E, Message),
    '$ga_py'(problem(condition(Id, Message)), _).
problem(action(Firing, K, E)) :- !,
    error_message(E, Message),
    '$ga_py'(problem(action(Firing, K, Message)), _).
problem(precondition(Index, E)) :- !,
    error_message(E, Message),
    '$ga_py'(problem(precondition(Index, Message)), _).
problem(Problem) :-
    '$ga_py'(problem(Problem), _).
