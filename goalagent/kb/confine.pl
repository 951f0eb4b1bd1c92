/*  What an agent's Prolog may call: every goal of agent text (knowledge, conditions,
    preconditions, directives, clauses it asserts) goes through prepare/3 before it is
    loaded, so each goal is checked once, when the program is loaded, with a located error
    for what is refused; goals only known at run time (call(G), findall(T, G, L) with G
    built by the program, assertz(C) of a built clause) are wrapped in call_checked/3,
    which checks them, the same way, when they run.

    Always (sandbox or not) -- minds are private and the runtime is not the agents' to
    change: no module qualification (M:G, @/2, assertz(M:C), dynamic(M:P), ...), no
    predicate whose name starts with '$' (SWI's internals and the runtime's), nothing that
    enumerates modules or atoms (module names could be read from them), nothing that
    changes what every agent shares (confine_builtins.pl); global variables, flags and
    recorded keys are each agent's own (confine_keys.pl), never unbound or reserved.

    With the sandbox, in addition, every built-in or library predicate called must be
    safe as SWI-Prolog's library(sandbox) defines it (safe_goal/1: no files, OS, network,
    processes, halt, flags, foreign code, consult, ...): a whitelist, not a blacklist.
    Directives are then only dynamic/1, discontiguous/1, op/3 and loading library modules.
*/
:- module(ga_confine, []).

:- use_module(library(apply)).
:- use_module(library(yall)).               % these define meta-predicates agents use: their
:- use_module(library(aggregate)).          % goal arguments are found through the imports
:- use_module(library(solution_sequences)).
:- use_module(library(lists)).
:- use_module(library(prolog_format), [format_spec/2]).

:- set_prolog_flag(generate_debug_info, false).

:- include(confine_builtins).
:- include(confine_keys).

%   Placeholders for goal arguments when asking library(sandbox) about a meta-predicate
%   (the arguments themselves are checked here, one by one).
free.
free(_).
free(_, _).
free(_, _, _).
free(_, _, _, _).
free(_, _, _, _, _).
free(_, _, _, _, _, _).
free(_, _, _, _, _, _, _).
free(_, _, _, _, _, _, _, _).

:- multifile sandbox:safe_primitive/1.
sandbox:safe_primitive(ga_confine:free).
sandbox:safe_primitive(ga_confine:free(_)).
sandbox:safe_primitive(ga_confine:free(_, _)).
sandbox:safe_primitive(ga_confine:free(_, _, _)).
sandbox:safe_primitive(ga_confine:free(_, _, _, _)).
sandbox:safe_primitive(ga_confine:free(_, _, _, _, _)).
sandbox:safe_primitive(ga_confine:free(_, _, _, _, _, _)).
sandbox:safe_primitive(ga_confine:free(_, _, _, _, _, _, _)).
sandbox:safe_primitive(ga_confine:free(_, _, _, _, _, _, _, _)).

		 /*******************************
		 *          PREPARING           *
		 *******************************/

%!  prepare(+Goal0, +Ctx, -Goal) is det.
%   Goal0 checked (throws ga_refused(Why) for what is not allowed) and with every goal
%   only known at run time wrapped in call_checked/3. Ctx = c(Module, Sandbox, Own):
%   the agent's module, true/false, and a list of Name/Arity it defines itself (runtime
%   when call_checked/3 prepares a goal as it runs: arguments still unbound stay so).

prepare(G, Ctx, Checked) :-
    var(G), !,
    checked(Ctx, G, Checked).
prepare((A0, B0), Ctx0, (A, B)) :- !,
    inner(Ctx0, Ctx),
    prepare(A0, Ctx, A),
    prepare(B0, Ctx, B).
prepare((A0 ; B0), Ctx0, (A ; B)) :- !,
    inner(Ctx0, Ctx),
    prepare(A0, Ctx, A),
    prepare(B0, Ctx, B).
prepare((A0 -> B0), Ctx0, (A -> B)) :- !,
    inner(Ctx0, Ctx),
    prepare(A0, Ctx, A),
    prepare(B0, Ctx, B).
prepare((A0 *-> B0), Ctx0, (A *-> B)) :- !,
    inner(Ctx0, Ctx),
    prepare(A0, Ctx, A),
    prepare(B0, Ctx, B).
prepare(\+ A0, Ctx0, \+ A) :- !,
    inner(Ctx0, Ctx),
    prepare(A0, Ctx, A).
prepare(not(A0), Ctx0, not(A)) :- !,
    inner(Ctx0, Ctx),
    prepare(A0, Ctx, A).
prepare(M:G, _, _) :- !,
    refuse("~q is qualified with a module: an agent calls in its own mind only", [M:G]).
prepare(G, _, _) :-
    \+ callable(G), !,
    refuse("~q is not a goal", [G]).
prepare(G0, c(M, Sb, _), G) :-                 % a lambda (library(yall)) applied: its body
    compound(G0),                               % is checked as a goal whose variables are
    compound_name_arguments(G0, >>, [Ps, B0|Extra]), !,   % bound later (by the call)
    prepare(B0, c(M, Sb, []), B),
    compound_name_arguments(G, >>, [Ps, B|Extra]).
prepare(throw(Ball), _, Prepared) :- !,         % the runtime's exceptions are not the
    (   runtime_ball(Ball)                      % agent's to throw: '$aborted' stopped the
    ->  refuse_ball(Ball)                       % whole run as Ctrl-C does
    ;   ground(Ball)
    ->  Prepared = throw(Ball)
    ;   Prepared = ga_confine:agent_throw(Ball)
    ).
prepare(apply(G0, Extra), Ctx, Prepared) :- !,  % apply/2: a goal with arguments added
    (   callable(G0), is_list(Extra)
    ->  extend(G0, Extra, G),
        prepare(G, Ctx, Prepared)
    ;   arg(3, Ctx, runtime)
    ->  throw(error(instantiation_error, _))
    ;   checked(Ctx, apply(G0, Extra), Prepared)
    ).
prepare(G, Ctx, Prepared) :-
    functor(G, Name, Arity),
    (   sub_atom(Name, 0, _, _, $)
    ->  refuse("~q/~w is reserved for SWI-Prolog and the runtime", [Name, Arity])
    ;   own(G, Ctx)                           % the agent's own told/0, append/1, ...
    ->  Prepared = G
    ;   private(Name/Arity)
    ->  refuse("~q/~w would reveal other agents' or the runtime's modules", [Name, Arity])
    ;   process_wide(Name/Arity)
    ->  refuse("~q/~w would end or change the whole process, every agent in it", [Name, Arity])
    ;   attribute_hook(Name/Arity)
    ->  refuse("~q/~w makes the module it names run code (its attribute hooks); use freeze/2, when/2 or dif/2", [Name, Arity])
    ;   lambda(Name, Arity)
    ->  refuse("~q/~w: this lambda form (library(yall)) cannot be checked; write Params>>Body or a helper predicate", [Name, Arity])
    ;   \+ library_goal(G, Ctx)
    ->  library_refused(G, Ctx)
    ;   agent_counter(G, Ctx, Counter)        % gensym/2's counters: each agent's own
    ->  Prepared = Counter
    ;   agent_key(G, Ctx, G1),
        prepare_call(G1, Ctx, Prepared)
    ).

%   inner(+Ctx0, -Ctx): the context of a goal inside Ctx0's goal (a conjunct, a meta
%   argument, a clause body). When call_checked/3 prepares the goal it is about to call,
%   what is unbound now stays so for that goal only: a goal inside it may be called after
%   another one bound its variables ((X = M:G, assertz(X))), so it is prepared as when
%   loading, with what is not known yet checked when it is called.
inner(c(M, Sb, runtime), c(M, Sb, [])) :- !.
inner(Ctx, Ctx).

%   A predicate the agent defines itself: its clauses are prepared where they are loaded.
%   (also one SWI-Prolog has that the agent made its own, see make_own/2: implementation_module/1
%   is asked because it does not link M to a library's or the system's predicate).
own(G, c(M, _, Own)) :-
    functor(G, Name, Arity),
    (   Own \== runtime,
        memberchk(Name/Arity, Own)
    ->  true
    ;   predicate_property(M:G, implementation_module(M)),
        predicate_property(M:G, defined)
    ).

%   A built-in or library predicate: its goal and module arguments are checked (or the
%   whole call is left to run time when one is not known yet); under the sandbox it must
%   be safe.
prepare_call(G, Ctx, Prepared) :-
    (   format_goal(G)
    ->  fail                                % refused above if it could run a goal
    ;   printing_goal(G),
        \+ ground(G),
        \+ arg(3, Ctx, runtime)
    ->  checked(Ctx, G, Prepared)           % its text checked when it is printed
    ;   format_sized(G, Ctx)
    ->  checked(Ctx, G, Prepared)           % its counts checked when it runs
    ;   ga_sizes:sized(G, Ctx, Sized)       % what it makes bounded before it starts
    ->  sandbox_allows(G, Ctx),
        Prepared = Sized
    ;   meta_specs(G, Specs)
    ->  G =.. [Name|Args0],
        (   catch(maplist(prepare_arg(Ctx), Specs, Args0, Args), ga_later, fail)
        ->  Allowed =.. [Name|Args],
            sandbox_allows(Allowed, Ctx),
            stoppable(Allowed, Ctx, Prepared)
        ;   checked(Ctx, G, Prepared)     % call_checked/3 asks the sandbox when it runs
        )
    ;   predicate_property(system:G, transparent),
        \+ ground(G),
        \+ arg(3, Ctx, runtime)
    ->  checked(Ctx, G, Prepared)         % module-sensitive (abolish/1, clause/3, ...):
                                          % its arguments checked when it runs
    ;   predicate_property(system:G, transparent),
        sub_term(Q, G), nonvar(Q), Q = M:_, atom(M)
    ->  refuse("~q names the module ~q: an agent reaches its own mind only", [G, M])
    ;   predicate_property(system:G, transparent),
        sub_term(Q, G), nonvar(Q), ( Q = N/_ ; Q = N//_ ), atom(N), sub_atom(N, 0, _, _, $)
    ->  refuse("~q names ~q, reserved for SWI-Prolog and the runtime", [G, Q])
    ;   Prepared = G,
        sandbox_allows(G, Ctx)
    ).

%   format/1,2,3 run goals written as ~@ in their format: only a known format without ~@
%   (format_goal/1 refuses the others and fails for these).
format_goal(G) :-
    (   G = format(F) ; G = format(F, _) ; G = format(_, F, _) ),
    !,
    (   var(F)
    ->  refuse("format/2,3 with a format only known at run time", [])
    ;   text_contains(F, "~@")
    ->  refuse("format's ~~@ calls a goal; write the goal's output another way", [])
    ;   text_contains(F, "~W"),
        \+ ground(G)
    ->  refuse("format's ~~W with write options only known at run time", [])
    ;   hidden_call(G)
    ->  refuse("~q: its write options call a goal (portray_goal)", [G])
    ;   format_counts(F, G, Counts),
        max_format_count(Max),
        member(N, Counts), integer(N), N > Max
    ->  refuse("format ~q repeats or pads ~D characters, more than ~D (an output or memory bomb SWI-Prolog cannot interrupt)", [F, N, Max])
    ;   fail
    ).
format_goal(G) :-
    printing_goal(G),
    hidden_call(G),
    refuse("~q would call a goal hidden in its text (~~@) or options (portray_goal)", [G]).

%   format_counts(+Format, +G, -Counts): the repeat counts, columns and digits of Format's
%   directives (~100c, ~*c with its argument, ~30|, ~2f); an argument not known yet is a
%   variable. SWI-Prolog writes what they ask for in C without looking at signals: a
%   count of 1,000,000,000 wrote 1 GB to the terminal, 30 s past the time limit.
format_counts(Format, G, Counts) :-
    catch(format_spec(Format, Spec), _, fail),
    (   G = format(_) -> Args0 = [] ; G =.. [_|GArgs], last(GArgs, Args0) ),
    (   is_list(Args0) -> Args = Args0 ; Args = [Args0] ),
    spec_counts(Spec, Args, Counts).

spec_counts([], _, []).
spec_counts([escape(Num, _, Directive)|Spec], Args0, Counts) :- !,
    (   Num = number(N)
    ->  Counts = [N|Counts1], Args1 = Args0
    ;   Num == star
    ->  ( Args0 = [N|Args1] -> Counts = [N|Counts1] ; Counts = Counts1, Args1 = [] )
    ;   Counts = Counts1, Args1 = Args0
    ),
    directive_arity(Directive, Arity),
    (   length(Used, Arity), append(Used, Args2, Args1) -> true ; Args2 = [] ),
    spec_counts(Spec, Args2, Counts1).
spec_counts([_|Spec], Args, Counts) :-
    spec_counts(Spec, Args, Counts).

directive_arity(D, 0) :- memberchk(D, [t, '|', '+', n, '~']), !.
directive_arity('W', 2) :- !.
directive_arity(_, 1).

max_format_count(100000).

%   format_sized(+G, +Ctx): G is a format call whose counts are only known at run time.
format_sized(G, Ctx) :-
    \+ arg(3, Ctx, runtime),
    ( G = format(F, _) ; G = format(_, F, _) ),
    \+ ground(G),
    format_counts(F, G, Counts),
    member(N, Counts), var(N), !.

%   hidden_call(@G): some argument of G is text holding ~@ (an atom, string or list of
%   codes or characters) or a write option portray_goal(_).
hidden_call(G) :-
    sub_term(T, G),
    nonvar(T),
    (   T = portray_goal(_)
    ;   ( atom(T) ; string(T) ), sub_string(T, _, _, _, "~@")
    ;   T = [C1, C2|_], nonvar(C1), nonvar(C2),
        ( C1 == 0'~ ; C1 == '~' ), ( C2 == 0'@ ; C2 == '@' )
    ),
    !.

text_contains(Text, Part) :-
    catch(( text_to_string(Text, String), sub_string(String, _, _, _, Part) ), _, fail).

meta_specs(G, Specs) :-
    (   predicate_property(system:G, meta_predicate(Head))
    ->  true
    ;   functor(G, Name, Arity),
        functor(Probe, Name, Arity),
        predicate_property(Probe, meta_predicate(Head)),
        predicate_property(Probe, imported_from(_))
    ),
    Head =.. [_|Specs],
    once(( member(Spec, Specs), goal_spec(Spec) )).
meta_specs(G, Specs) :-
    assert_family(G),
    G =.. [_|Args],
    findall(S, ( member(_, Args), S = (:) ), Specs).

goal_spec(S) :- integer(S), !.
goal_spec(^).
goal_spec(//).
goal_spec(:).

%   One argument of a meta-predicate call: a goal (spec N: with N more arguments), a
%   clause or predicate (spec :), or data. ga_later: not known before run time.
prepare_arg(Ctx0, 0, A0, A) :- !,
    inner(Ctx0, Ctx),
    (   var(A0) -> checked_later(A0, Ctx, A) ; prepare(A0, Ctx, A) ).
prepare_arg(Ctx0, ^, A0, A) :- !,
    inner(Ctx0, Ctx),
    (   var(A0) -> checked_later(A0, Ctx, A) ; strip_carets(A0, Ctx, A) ).
prepare_arg(Ctx, N, A0, A) :-
    integer(N), !,
    (   var(A0)
    ->  Ctx = c(M, Sb, _),                % a closure bound later: checked when called
        A = ga_confine:closure_checked(Sb, M, A0)
    ;   A0 = _:_
    ->  refuse("~q is qualified with a module: an agent calls in its own mind only", [A0])
    ;   callable(A0)
    ->  length(Extra, N),
        extend(A0, Extra, Goal),
        Ctx = c(M, Sb, _),                % Extra: arguments only known when it is called
        (   catch(prepare(Goal, c(M, Sb, []), Prepared), ga_later, fail),
            Prepared == Goal              % nothing in it to check later (e.g. a lambda's
        ->  A = A0                        % body with a wrapped call: checked when called)
        ;   A = ga_confine:closure_checked(Sb, M, A0)  % checked when it is called
        )
    ;   refuse("~q is not a goal", [A0])
    ).
prepare_arg(Ctx, //, A0, A) :- !,
    prepare_grammar(A0, Ctx, A).
prepare_arg(Ctx, :, A0, A) :- !,
    prepare_module_arg(A0, Ctx, A).
prepare_arg(_, _, A, A).

%   prepare_grammar(+Body0, +Ctx, -Body): a grammar body (the argument of phrase/2,3,
%   call_dcg/3, library(dcg/high_order), ...) checked as the goal SWI-Prolog translates it
%   to: its {}/1 goals, its non-terminals with their two list arguments, call//N. A body
%   not known yet, or whose translation holds goals only known later, is translated and
%   checked again each time it is called (grammar_checked/5).
prepare_grammar(A0, c(M, Sb, Own), A) :-
    (   var(A0)
    ->  A = ga_confine:grammar_checked(Sb, M, A0)
    ;   A0 = _:_
    ->  refuse("~q is qualified with a module: an agent calls in its own mind only", [A0])
    ;   grammar_goal(A0, _, _, Goal),
        inner(c(M, Sb, Own), Ctx),
        prepare(Goal, Ctx, Prepared),
        (   Prepared == Goal
        ->  A = A0
        ;   A = ga_confine:grammar_checked(Sb, M, A0)
        )
    ).

%   grammar_goal(+Body, ?S0, ?S, -Goal): Goal runs Body from list S0 to S, as SWI-Prolog
%   translates grammar rules (dcg_translate_rule/2).
grammar_goal(Body, S0, S, Goal) :-
    (   catch(dcg_translate_rule(('$ga_grammar' --> Body), Clause), _, fail),
        Clause = ('$ga_grammar'(T0, T) :- Goal0)
    ->  T0 = S0, T = S, Goal = Goal0
    ;   refuse("~q is not a grammar body", [Body])
    ).

strip_carets(V^G0, Ctx, V^G) :- !,
    (   var(G0) -> checked_later(G0, Ctx, G) ; strip_carets(G0, Ctx, G) ).
strip_carets(G0, Ctx, G) :-
    prepare(G0, Ctx, G).

%   checked_later(+G0, +Ctx, -G): a goal not known yet (it may be bound by the very
%   meta-predicate that calls it, e.g. forall(member(G, L), G)): checked when it is called.
checked_later(G0, Ctx, G) :-
    checked(Ctx, G0, G).

%   checked(+Ctx, +G, -Checked): G called through call_checked/3 (Ctx's module and sandbox
%   written in, never taken from G: a goal bound to M:X at run time is refused there).
checked(c(M, Sb, _), G, ga_confine:call_checked(Sb, M, G)).

%   later(+Ctx): a clause or predicate argument not known yet. When loading: ga_later (the call is checked when
%   it runs, see call_checked/3); when it runs (Ctx's third argument is runtime): still
%   unbound, it can name no module nor goal -- the built-in raises its own error.
later(Ctx) :-
    (   arg(3, Ctx, runtime)
    ->  true
    ;   throw(ga_later)
    ).

extend(M:G, Extra, M:G1) :- !,
    extend(G, Extra, G1).
extend(G, Extra, G1) :-
    G =.. List0,
    append(List0, Extra, List),
    G1 =.. List.

%   A module-sensitive argument (a clause to assert, a predicate to declare, a head to
%   look up): never qualified; a clause's body is prepared like any goal.
prepare_module_arg(A, Ctx, A) :-
    var(A), !,
    later(Ctx).
prepare_module_arg(M:X, _, _) :- !,
    refuse("~q is qualified with a module: an agent changes its own mind only", [M:X]).
prepare_module_arg((H :- B0), Ctx0, (H :- B)) :- !,
    clause_head_allowed(H),
    inner(Ctx0, Ctx),
    (   var(B0) -> checked_later(B0, Ctx, B) ; prepare(B0, Ctx, B) ).
prepare_module_arg(A, Ctx, A) :-
    (   specs(A)                            % dynamic([p/1, q/2]), op(700, xfx, [a, b]),
    ->  spec_allowed(A, Ctx)                % dynamic((p/1, q/2)), dynamic(p/1 as incremental)
    ;   callable(A)
    ->  clause_head_allowed(A)
    ;   true
    ).

specs([_|_]).
specs((_, _)).
specs(_ as _).

%   Each predicate or operator of a list, conjunction or `as` of them names neither a
%   module nor a reserved ('$') name.
spec_allowed(S, Ctx) :-
    (   var(S)
    ->  later(Ctx)
    ;   S == []
    ->  true
    ;   ( S = [A|B] ; S = (A, B) )
    ->  spec_allowed(A, Ctx),
        spec_allowed(B, Ctx)
    ;   S = (A as _)
    ->  spec_allowed(A, Ctx)
    ;   S = _:_
    ->  refuse("~q is qualified with a module: an agent changes its own mind only", [S])
    ;   ( S = N/_ ; S = N//_ ), atom(N), sub_atom(N, 0, _, _, $)
    ->  refuse("~q is reserved for SWI-Prolog and the runtime", [S])
    ;   true
    ).

clause_head_allowed(H) :-
    (   var(H)
    ->  true
    ;   H = M:_
    ->  refuse("~q is qualified with a module", [M])
    ;   callable(H), functor(H, Name, _), sub_atom(Name, 0, _, _, $)
    ->  refuse("~q is reserved for the runtime", [Name])
    ;   true
    ).

assert_family(G) :-
    functor(G, Name, Arity),
    memberchk(Name/Arity, [assert/1, asserta/1, assertz/1, assert/2, asserta/2, assertz/2,
                           retract/1, retractall/1]).

lambda(/, Arity) :- Arity >= 2.             % yall's Free/Lambda and \X^Body: copy rules
lambda(\, Arity) :- Arity >= 1.             % this check does not follow

%   library_goal(+G, +Ctx): G loads no code, or only a library module.
library_goal(G, Ctx) :-
    (   G = use_module(Spec) ; G = use_module(Spec, _) )
    ->  nonvar(Spec), Spec = library(L), library_name(L, Ctx)
    ;   true.

library_refused(G, c(_, true, _)) :- !,
    refuse("~q is not allowed in the sandbox: it loads code, and agents load only these libraries: ~w", [G, "lists, apply, aggregate, pairs, assoc, ordsets, ugraphs, rbtrees, nb_set, heaps, random, solution_sequences, yall, occurs, terms, sort, option, error, gensym, varnumbers, when, dif, dicts, strings, tables, dcg/basics, dcg/high_order"]).
library_refused(G, _) :-
    refuse("~q loads code into the process: only library modules (use_module(library(Name)))", [G]).

%   library_name(+L, +Ctx): a library of SWI-Prolog's own (library(lists), library(dcg/basics)),
%   never a path out of its folders (library('../../tmp/evil') would load any file); in
%   the sandbox one of a few whose loading changes nothing else in the process (many
%   libraries hook into how the whole process compiles code: library(apply_macros), which
%   library(clpfd) and others load, changes every file compiled after it).
library_name(L, Ctx) :-
    (   atom(L) -> Name = L ; term_to_atom(L, Name) ),
    split_string(Name, "/", "", Parts),
    forall(member(Part, Parts),
           ( string_chars(Part, [First|Rest]),
             char_type(First, lower),
             forall(member(C, Rest), ( char_type(C, alnum) ; C == '_' )) )),
    (   arg(2, Ctx, true)
    ->  sandbox_library(Name)
    ;   true
    ).

%   Looking at the agent's own predicates: library(sandbox) refuses these because a module
%   could be named in them, which prepare/3 has refused already.
own_introspection(current_predicate(_)).
own_introspection(current_predicate(_, _)).
own_introspection(predicate_property(_, _)).

placeholders(G, Probe) :-
    (   predicate_property(system:G, meta_predicate(Head))
    ->  G =.. [Name|Args],
        Head =.. [_|Specs],
        maplist(placeholder, Specs, Args, ProbeArgs),
        Probe =.. [Name|ProbeArgs]
    ;   Probe = G
    ).

placeholder(0, _, ga_confine:free) :- !.
placeholder(^, _, ga_confine:free) :- !.
placeholder(N, _, ga_confine:free) :- integer(N), !.
placeholder(//, _, ga_confine:free) :- !.
placeholder(_, A, A).

unsafe(error(permission_error(call, sandboxed, Culprit), _), G) :- !,
    functor(Culprit, Name, Arity),
    (   functor(G, Name, Arity)
    ->  refuse("~q/~w is not allowed in the sandbox", [Name, Arity])
    ;   refuse("~q is not allowed in the sandbox (it calls ~q/~w)", [G, Name, Arity])
    ).
unsafe(error(existence_error(procedure, Missing), _), G) :-
    missing_predicate(Missing, Name, Arity),
    functor(G, Name, Arity), !.          % neither built-in nor library: the agent's own
unsafe(error(existence_error(procedure, PI), _), _) :- !,
    refuse("~q is not a predicate the sandbox knows", [PI]).
unsafe(error(instantiation_error, _), G) :- !,
    refuse("the sandbox cannot tell what ~q calls", [G]).
unsafe(E, G) :-
    refuse("the sandbox refuses ~q: ~q", [G, E]).

missing_predicate(_:X, Name, Arity) :- !,
    missing_predicate(X, Name, Arity).
missing_predicate(Name/Arity, Name, Arity) :- !.
missing_predicate(Head, Name, Arity) :-
    callable(Head),
    functor(Head, Name, Arity).

refuse(Format, Args) :-
    format(string(Why), Format, Args),
    throw(ga_refused(Why)).

		 /*******************************
		 *     WHAT AGENT TEXT HOLDS    *
		 *******************************/

%!  prepare_clause(+Clause0, +Ctx, -Clause) is det.
%   A knowledge or belief clause: its head is the agent's own, its body prepared.
prepare_clause((H :- B0), Ctx, (H :- B)) :- !,
    clause_head_allowed(H),
    prepare(B0, Ctx, B).
prepare_clause(H, _, H) :-
    clause_head_allowed(H).

%!  prepare_directive(+Directive0, +Ctx, -Directive) is det.
%   Declarations (dynamic, discontiguous, op) of the agent's own predicates and operators,
%   loading library modules; under the sandbox nothing else, otherwise any goal as
%   prepare/3 allows it.
prepare_directive(D, _, _) :-
    var(D), !,
    refuse("a directive must be known when the program is loaded", []).
prepare_directive(D, c(M, Sb, _), D) :-
    declaration(D), !,
    arg(1, D, Spec),
    unqualified(Spec),
    spec_allowed(Spec, c(M, Sb, runtime)).     % run now: what is unbound stays so
prepare_directive(op(P, T, Names), _, op(P, T, Names)) :- !,
    unqualified(Names).
prepare_directive(D, Ctx, D) :-
    library_load(D, Ctx), !.
prepare_directive(initialization(G), Ctx, Prepared) :- !,   % run as the program is loaded,
    prepare_directive(G, Ctx, Prepared).                     % as any directive
prepare_directive(initialization(G, now), Ctx, Prepared) :- !,
    prepare_directive(G, Ctx, Prepared).
prepare_directive(initialization(G, When), _, _) :- !,
    refuse("initialization(~q, ~q): an agent's program runs only as it is loaded (initialization/1)", [G, When]).
prepare_directive(D, c(M, true, O), _) :-
    ( D = use_module(_) ; D = use_module(_, _) ; D = ensure_loaded(_) ), !,
    library_refused(D, c(M, true, O)).
prepare_directive(D, c(_, true, _), _) :- !,
    refuse("the directive ~q is not allowed in the sandbox (only dynamic, discontiguous, op and loading library modules)", [D]).
prepare_directive(D, Ctx, Prepared) :-
    prepare(D, Ctx, Prepared).

declaration(dynamic(_)).
declaration(discontiguous(_)).

library_load(use_module(library(L)), Ctx) :- library_name(L, Ctx).
library_load(use_module(library(L), _), Ctx) :- library_name(L, Ctx).
library_load(ensure_loaded(library(L)), Ctx) :- library_name(L, Ctx).

unqualified(X) :- var(X), !.
unqualified(M:X) :- !,
    refuse("~q is qualified with a module", [M:X]).
unqualified(X) :-
    compound(X), !,
    X =.. [_|Args],
    maplist(unqualified, Args).
unqualified(_).

%!  prepare_condition(+Cond0, +B, -Cond) is det.
%   A rule's condition as mentalstate_load.pl's compile/5 reads it: the queries inside its
%   '$bel'/'$goal'/'$agoal'/'$goala' literals prepared for the agent of belief module B. A
%   refused query throws ga_refused_literal(I, Why), I counting its mental literals from 0
%   (those under \+ included, left to right).
prepare_condition(Cond0, B, Cond) :-
    context(B, Ctx),
    prepare_literals(Cond0, Ctx, Cond, 0, _).

%!  prepare_sandboxed_condition(+Cond0, +B, -Cond) is det.
%   As prepare_condition/3, and in the sandbox whether or not the agent is: a condition
%   written in the mind inspector's page inspects a mind and changes nothing outside it
%   (the agent's own predicates it calls run as the agent loaded them).
prepare_sandboxed_condition(Cond0, B, Cond) :-
    load_sandbox,
    prepare_literals(Cond0, c(B, true, []), Cond, 0, _).

prepare_literals((A0, B0), Ctx, (A, B), I0, I) :- !,
    prepare_literals(A0, Ctx, A, I0, I1),
    prepare_literals(B0, Ctx, B, I1, I).
prepare_literals(\+ A0, Ctx, \+ A, I0, I) :- !,
    prepare_literals(A0, Ctx, A, I0, I).
prepare_literals(true, _, true, I, I) :- !.
prepare_literals('$percept'(Q), _, '$percept'(Q), I0, I) :- !,
    I is I0 + 1.
prepare_literals(Literal0, Ctx, Literal, I0, I) :-
    Literal0 =.. [Op, Q0],
    catch(prepare(Q0, Ctx, Q), ga_refused(Why), throw(ga_refused_literal(I0, Why))),
    Literal =.. [Op, Q],
    I is I0 + 1.

%!  prepare_query(+Query0, +B, -Query) is det.
%   A query the runtime runs for the agent of belief module B (a precondition, a drop).
prepare_query(Q0, B, Q) :-
    context(B, Ctx),
    prepare(Q0, Ctx, Q).

context(B, c(B, Sandbox, [])) :-
    (   catch(B:'$ga_confine'(Sandbox0), _, fail)
    ->  Sandbox = Sandbox0
    ;   Sandbox = false
    ).

		 /*******************************
		 *           RUN TIME           *
		 *******************************/

%!  call_checked(+Sandbox, +Module, +Goal) is nondet.
%   Calls Goal of the agent whose module is Module, known only now, after preparing it as
%   prepare/3 does when loading: a goal that is refused raises ga_refused(Why) (the rule
%   is then not applicable, with a warning). Not a meta-predicate: Goal comes as the
%   program built it, so a module it names is seen (and refused).
call_checked(Sb, M, G) :-
    prepare(G, c(M, Sb, runtime), Prepared),
    (   Prepared = ga_confine:call_checked(_, _, G1), G1 == G
    ->  throw(error(instantiation_error, _))
    ;   call(M:Prepared)
    ).

%!  closure_checked(+Sandbox, +Module, +Closure, ?A1, ...) is nondet.
%   A closure whose goal depends on the arguments it gets (maplist(assertz, Clauses),
%   call(P, X)): the goal is checked as call_checked/3 does when it is called.
closure_checked(Sb, M, C, A1) :- closure_goal(Sb, M, C, [A1]).
closure_checked(Sb, M, C, A1, A2) :- closure_goal(Sb, M, C, [A1, A2]).
closure_checked(Sb, M, C, A1, A2, A3) :- closure_goal(Sb, M, C, [A1, A2, A3]).
closure_checked(Sb, M, C, A1, A2, A3, A4) :- closure_goal(Sb, M, C, [A1, A2, A3, A4]).
closure_checked(Sb, M, C, A1, A2, A3, A4, A5) :-
    closure_goal(Sb, M, C, [A1, A2, A3, A4, A5]).
closure_checked(Sb, M, C, A1, A2, A3, A4, A5, A6) :-
    closure_goal(Sb, M, C, [A1, A2, A3, A4, A5, A6]).
closure_checked(Sb, M, C, A1, A2, A3, A4, A5, A6, A7) :-
    closure_goal(Sb, M, C, [A1, A2, A3, A4, A5, A6, A7]).

%!  grammar_checked(+Sandbox, +Module, +Body, ?S0, ?S) is nondet.
%   A grammar body only known when it runs (see prepare_grammar/3), called as a
%   non-terminal: translated, checked as call_checked/3 checks a goal, and called.
grammar_checked(Sb, M, Body, S0, S) :-
    (   var(Body)
    ->  throw(error(instantiation_error, _))
    ;   Body = _:_
    ->  refuse("~q is qualified with a module: an agent calls in its own mind only", [Body])
    ;   grammar_goal(Body, S0, S, Goal),
        prepare(Goal, c(M, Sb, []), Prepared),
        call(M:Prepared)
    ).

closure_goal(Sb, M, C, Args) :-
    (   var(C)
    ->  throw(error(instantiation_error, _))
    ;   C = _:_
    ->  refuse("~q is qualified with a module: an agent calls in its own mind only", [C])
    ;   extend(C, Args, G),
        call_checked(Sb, M, G)
    ).
