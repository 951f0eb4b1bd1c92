/*  Guards on what agents' text may be: how deep a term may nest, and what a file of facts
    (--load-beliefs) may hold. Loaded once per process beside mentalstate.pl; Python
    (goalagent/kb/engine.py, facts.py) calls the predicates below.

    Depth is counted as Python converts terms (goalagent/kb/engine.py, terms.py recurse once
    per level): a compound's arguments and a list's elements are one level down, a list's
    tail is not (lists are converted in a loop), so long lists are fine and only real
    nesting is bounded.
*/
:- module(ga_guard, []).

:- set_prolog_flag(generate_debug_info, false).
%   Its arithmetic (depths, offsets, clause counts: integers it makes itself) inline: a
%   cycle runs belief_bound/2 (this file only).
:- set_prolog_flag(optimise, true).

%!  max_depth(-Depth) is det.
%   The deepest nesting of a term read from an agent's text or a file of facts.
max_depth(200).

		 /*******************************
		 *            DEPTH             *
		 *******************************/

%!  check_depth(+Text, +Term) is det.
%   Throws error(syntax_error(Message), exact(Offset)) at the first subterm of Term (read
%   from Text with ga_read's operators) nested deeper than max_depth/1.
check_depth(Text, Term) :-
    max_depth(Max),
    (   within(Term, Max)
    ->  true
    ;   deep_offset_in_text(Text, Max, Offset),
        depth_message(Max, Message),
        throw(error(syntax_error(Message), exact(Offset)))
    ).

depth_message(Max, Message) :-
    format(string(Message), "term nested more than ~w levels deep", [Max]).

%!  within(@Term, +Depth) is semidet.
%   Term nests no deeper than Depth (compound arguments and list elements one level down).
within(Term, Depth) :-
    (   compound(Term)
    ->  Depth > 0,
        Down is Depth - 1,
        (   Term = [_|_]
        ->  within_list(Term, Depth, Down)
        ;   compound_name_arity(Term, _, Arity),
            within_args(1, Arity, Term, Down)
        )
    ;   true
    ).

within_list(List, Depth, Down) :-
    (   nonvar(List),
        List = [Head|Tail]
    ->  within(Head, Down),
        within_list(Tail, Depth, Down)
    ;   within(List, Depth)
    ).

within_args(I, Arity, Term, Down) :-
    (   I > Arity
    ->  true
    ;   arg(I, Term, Arg),
        within(Arg, Down),
        I1 is I + 1,
        within_args(I1, Arity, Term, Down)
    ).

deep_offset_in_text(Text, Max, Offset) :-
    string_concat(Text, "\n. ", Full),
    catch(setup_call_cleanup(
              open_string(Full, Stream),
              read_term(Stream, Term, [subterm_positions(Pos), module(ga_read)]),
              close(Stream)),
          _, fail),
    deep_offset(Term, Pos, Max, Offset),
    !.
deep_offset_in_text(_, _, 0).

%!  deep_offset(+Term, +Pos, +Depth, -Offset) is semidet.
%   The start of the first compound subterm of Term below Depth levels (Pos: its
%   subterm_positions).
deep_offset(Term, parentheses_term_position(_, _, Inner), Depth, Offset) :- !,
    deep_offset(Term, Inner, Depth, Offset).
deep_offset(Term, Pos, Depth, Offset) :-
    compound(Term),
    (   Depth =:= 0
    ->  position_start(Pos, Offset)
    ;   Down is Depth - 1,
        deep_offset_args(Term, Pos, Depth, Down, Offset)
    ).

deep_offset_args(Term, list_position(_, _, Elements, TailPos), Depth, Down, Offset) :- !,
    list_parts(Term, Elements, Items, Tail),
    (   member(Item-ItemPos, Items),
        deep_offset(Item, ItemPos, Down, Offset)
    ->  true
    ;   TailPos \== none,
        deep_offset(Tail, TailPos, Depth, Offset)
    ).
deep_offset_args(Term, term_position(_, _, _, _, ArgsPos), _, Down, Offset) :- !,
    compound_name_arguments(Term, _, Args),
    pairs_keys_values(Pairs, Args, ArgsPos),
    member(Arg-ArgPos, Pairs),
    deep_offset(Arg, ArgPos, Down, Offset),
    !.
deep_offset_args({Arg}, brace_term_position(_, _, ArgPos), _, Down, Offset) :- !,
    deep_offset(Arg, ArgPos, Down, Offset).
deep_offset_args(_, Pos, _, _, Offset) :-
    position_start(Pos, Offset).

list_parts(Tail, [], [], Tail) :- !.
list_parts([Item|Items], [Pos|Positions], [Item-Pos|Pairs], Tail) :-
    list_parts(Items, Positions, Pairs, Tail).

position_start(From-_, From) :- !.
position_start(Pos, From) :-
    compound(Pos),
    arg(1, Pos, From),
    integer(From),
    !.
position_start(_, 0).

		 /*******************************
		 *        FILES OF FACTS        *
		 *******************************/

%!  read_facts(+Text, +Key, +Checks, -Result) is det.
%   Reads every clause of Text (a file's content) with SWI's reader and ga_read's
%   operators, and checks that each is a fact: no directive (nothing is run), no rule, no
%   variable, no control construct or module qualification, no built-in or reserved ('$')
%   predicate, nesting within max_depth/1; and that the facts of the predicates Checks
%   speak of satisfy them (Checks: texts '$check'(Template, Condition, Meaning), e.g.
%   '$check'(afford(O, A, E, T, S, R), (integer(T), T >= 0), "Tot is ...")). Result =
%   ok(Count): the facts are kept under the global variable Key (see load_facts/4,
%   forget_facts/1); or error(Offset, Message) for the first bad clause (Offset: the
%   character where it starts).
read_facts(Text, Key, Checks, Result) :-
    catch(( maplist(read_check, Checks, Parsed),
            setup_call_cleanup(open_string(Text, Stream),
                               read_all(Stream, Parsed, Facts),
                               close(Stream)) ),
          E, true),
    (   var(E)
    ->  nb_setval(Key, Facts),
        length(Facts, Count),
        Result = ok(Count)
    ;   E = ga_bad(Offset, Message)
    ->  Result = error(Offset, Message)
    ;   E = error(syntax_error(What), Context)
    ->  ga_kb:syntax_message(What, Message0),
        format(string(Message), "syntax error: ~w", [Message0]),
        syntax_offset(Context, Offset),
        Result = error(Offset, Message)
    ;   ga_kb:error_message(E, Message),
        Result = error(0, Message)
    ).

read_check(Text, Check) :-
    term_string(Check, Text).

syntax_offset(stream(_, _, _, Char), Char) :- integer(Char), !.
syntax_offset(string(_, Char), Char) :- integer(Char), !.
syntax_offset(_, 0).

read_all(Stream, Checks, Facts) :-
    read_term(Stream, Term, [subterm_positions(Pos), variable_names(Names),
                             syntax_errors(error), module(ga_read)]),
    (   Term == end_of_file
    ->  Facts = []
    ;   position_start(Pos, Offset),
        check_fact(Term, Pos, Offset, Names),
        check_types(Checks, Term, Offset),
        Facts = [Offset-Term|More],
        read_all(Stream, Checks, More)
    ).

%   check_types(+Checks, +Fact, +Offset): Fact satisfies every check made for it.
check_types([], _, _).
check_types(['$check'(Template, Condition, Meaning)|Checks], Fact, Offset) :-
    (   \+ \+ Template = Fact,
        \+ ( copy_term(Template-Condition, Fact-Goal),
             catch(Goal, _, fail) )
    ->  format(string(Why), "~W: ~w", [Fact, [quoted(true), max_depth(12)], Meaning]),
        bad(Offset, Why)
    ;   check_types(Checks, Fact, Offset)
    ).

check_fact(Term, _, Offset, _) :-
    var(Term), !,
    bad(Offset, "a variable is not a fact").
check_fact(Term, _, Offset, _) :-
    not_a_fact(Term, Why), !,
    bad(Offset, Why).
check_fact(Term, _, Offset, Names) :-
    \+ ground(Term), !,
    term_variables(Term, [Var|_]),
    (   member(Name=V, Names), V == Var
    ->  true
    ;   Name = '_'
    ),
    format(string(Why), "a fact must be ground: ~w is a variable", [Name]),
    bad(Offset, Why).
check_fact(Term, Pos, _, _) :-
    max_depth(Max),
    \+ within(Term, Max), !,
    (   deep_offset(Term, Pos, Max, Offset)
    ->  true
    ;   position_start(Pos, Offset)
    ),
    depth_message(Max, Why),
    bad(Offset, Why).
check_fact(_, _, _, _).

%!  not_a_fact(+Term, -Why) is semidet.
not_a_fact((:- _), "a directive; a file of facts holds facts only (nothing was run)").
not_a_fact((?- _), "a directive; a file of facts holds facts only (nothing was run)").
not_a_fact((_ :- _), "a rule; a file of facts holds facts only").
not_a_fact((_ --> _), "a grammar rule; a file of facts holds facts only").
not_a_fact(_:_, "a module-qualified clause; a file of facts holds plain facts only").
not_a_fact(Term, Why) :-
    \+ callable(Term),
    format(string(Why), "~q is not a fact (not an atom or compound term)", [Term]).
not_a_fact(Term, Why) :-
    ga_kb:control(Term),
    functor(Term, Name, Arity),
    format(string(Why), "~q/~w is a control construct, not a fact", [Name, Arity]).
not_a_fact(Term, Why) :-
    functor(Term, Name, Arity),
    sub_atom(Name, 0, _, _, $),
    format(string(Why), "~q/~w is reserved for the runtime", [Name, Arity]).
not_a_fact(Term, Why) :-
    predicate_property(system:Term, defined),
    functor(Term, Name, Arity),
    format(string(Why), "~q/~w is a built-in predicate, not a belief", [Name, Arity]).

bad(Offset, Why) :-
    throw(ga_bad(Offset, Why)).

%!  load_facts(+B, +G, +Key, -Result) is det.
%   Adds the facts kept under Key to the belief module B (declared in the goal module G)
%   as insert/1 would, each once, in file order. Result = added(N) (how many were new) or
%   error(Offset, Message) for a fact B cannot take (e.g. of a knowledge predicate).
load_facts(B, G, Key, Result) :-
    nb_getval(Key, Pairs),
    sort(2, @<, Pairs, Unique),             % each fact once ...
    sort(1, @=<, Unique, Ordered),          % ... in file order
    findall(N/A, ( member(_-F, Ordered), functor(F, N, A) ), PIs0),
    sort(PIs0, PIs),
    include(has_clauses(B), PIs, Before),
    catch(( foldl(load_fact(B, G, Before), Ordered, 0, Added),
            Result = added(Added) ),
          ga_bad(Offset, Message),
          Result = error(Offset, Message)).

has_clauses(B, Name/Arity) :-
    functor(Head, Name, Arity),
    predicate_property(B:Head, number_of_clauses(C)),
    C > 0.

%   A fact of a predicate that had clauses before the load may be there already.
load_fact(B, G, Before, Offset-Fact, N0, N) :-
    functor(Fact, Name, Arity),
    (   memberchk(Name/Arity, Before),
        clause(B:Fact, true)
    ->  N = N0
    ;   catch(assertz(B:Fact), E, ( ga_kb:error_message(E, Message),
                                    throw(ga_bad(Offset, Message)) )),
        ga_kb:ensure_dynamic(G, Fact),
        N is N0 + 1
    ).

%!  forget_facts(+Key) is det.
%   Frees what is kept under Key (a file of facts, the facts a watch saw).
forget_facts(Key) :-
    (   nb_current(Key, _)
    ->  nb_delete(Key)
    ;   true
    ).

		 /*******************************
		 *        WATCHING FACTS        *
		 *******************************/

%!  fact_changes(+B, +Key, +Name, +Arity, -Gained, -Lost) is det.
%   The facts of Name/Arity in the belief module B gained and lost since the last call
%   with Key (the first call: all are gained), each list in standard order. Only clauses
%   are read (facts), no agent code runs. The facts seen are kept under the global
%   variable Key (see forget_facts/1).
fact_changes(B, Key, Name, Arity, Gained, Lost) :-
    functor(Head, Name, Arity),
    (   current_predicate(_, B:Head)
    ->  findall(Head, clause(B:Head, true), Now0),
        msort(Now0, Now)
    ;   Now = []
    ),
    (   nb_current(Key, Before)
    ->  true
    ;   Before = []
    ),
    ord_subtract(Now, Before, Gained),
    ord_subtract(Before, Now, Lost),
    (   Gained == [], Lost == []
    ->  true
    ;   nb_setval(Key, Now)
    ).

		 /*******************************
		 *            LIMITS            *
		 *******************************/

%!  stretch_signal(+Stretch, +Action) is det.
%   Sent to the main thread by the watchdog (goalagent/kb/watchdog.py): if the main
%   thread's Prolog is still in stretch number Stretch, abort it (Action = abort) or
%   throw ga_limit(time(T)) in it (Action = time(T)); a signal that comes late does nothing.
stretch_signal(Stretch, Action) :-
    '$ga_stretch'(now, Current),
    (   Current =:= Stretch
    ->  stretch_action(Action)
    ;   true
    ).

stretch_action(abort) :-
    abort.
stretch_action(time(T)) :-
    throw(ga_limit(time(T))).
stretch_action(call_memory(B, Max, Base, Page)) :-
    ga_memory:call_growth(B, Max, Base, Page).
stretch_action(held_memory(B, Max)) :-
    ga_memory:held_check(B, Max).

%!  aborted_rule(-Id) is det.
%   The rule the last aborted query was in (noted by rules.pl), or none; read once.
aborted_rule(Id) :-
    (   nb_current('$ga_aborted_rule', Id0),
        integer(Id0)
    ->  Id = Id0,
        nb_setval('$ga_aborted_rule', none)
    ;   Id = none
    ).

%!  set_limits(+B, +MaxInferences, +MaxBeliefs) is det.
%   The limits of the agent whose belief module is B (rules.pl's run/3 reads them).
set_limits(B, MaxInferences, MaxBeliefs) :-
    retractall(B:'$ga_limits'(_, _)),
    assertz(B:'$ga_limits'(MaxInferences, MaxBeliefs)).

%!  belief_bound(+B, +Max) is det.
%   Throws ga_limit(beliefs(N, Max)) when the agent of belief module B holds more than Max
%   clauses in its belief and goal modules. Counted only when the whole process holds more
%   than Max clauses (a counter SWI keeps), so the check costs nothing in ordinary runs.
belief_bound(B, Max) :-
    (   statistics(clauses, Total),
        Total =< Max
    ->  true
    ;   B:'$ga_gm'(G),
        module_clauses(B, NB),
        module_clauses(G, NG),
        N is NB + NG,
        (   N =< Max
        ->  true
        ;   throw(ga_limit(beliefs(N, Max)))
        )
    ).

module_clauses(M, N) :-
    aggregate_all(sum(C),
                  ( current_predicate(_, M:Head),
                    \+ predicate_property(M:Head, imported_from(_)),
                    predicate_property(M:Head, number_of_clauses(C)) ),
                  N).

%!  limit_message(+Limit, -Message) is det.
%   The words for ga_limit(Limit) in an error message.
limit_message(inferences(Max), Message) :- !,
    format(string(Message), "more than ~D inferences (--max-inferences)", [Max]).
limit_message(time(T), Message) :- !,
    format(string(Message), "ran longer than ~w s (--max-query-seconds)", [T]).
limit_message(beliefs(N, Max), Message) :- !,
    format(string(Message), "~D beliefs and goals, more than ~D (--max-beliefs)", [N, Max]).
limit_message(memory(held(Bytes), Max), Message) :- !,
    MB is -(-Bytes // 1048576), MaxMB is Max // 1048576,
    format(string(Message), "holds ~D MB in its clauses, records and global variables, \c
                             more than --max-memory ~D MB", [MB, MaxMB]).
limit_message(memory(call(Bytes), Max), Message) :- !,
    MB is -(-Bytes // 1048576), MaxMB is Max // 1048576,
    format(string(Message), "took ~D MB outside Prolog's stacks in one call, more than \c
                             --max-memory ~D MB", [MB, MaxMB]).
limit_message(Limit, Message) :-
    format(string(Message), "limit ~q", [Limit]).

%!  solutions(:Goal, +Template, +MaxInferences, +Count, -Rows) is det.
%   Rows: the instances of Template for all (Count = all) or the first Count solutions of
%   Goal, made with at most MaxInferences inferences; else ga_limit(inferences(Max)).
:- meta_predicate solutions(0, ?, +, +, -).

solutions(Goal, Template, Max, Count, Rows) :-
    (   Count == all
    ->  findall(Template-R, call_with_inference_limit(Goal, Max, R), Pairs)
    ;   findnsols(Count, Template-R, call_with_inference_limit(Goal, Max, R), Pairs),
        !
    ),
    (   memberchk(_-inference_limit_exceeded, Pairs)
    ->  Rows = ga_limit(inferences(Max))
    ;   acyclic_term(Pairs)                 % Python would read a cyclic list for ever
    ->  pairs_keys(Pairs, Rows)
    ;   throw(ga_error("an answer is a cyclic term (it contains itself)"))
    ).
