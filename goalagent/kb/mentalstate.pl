/*  Support predicates for goalagent's mental states (loaded once per process).

    One agent = two modules: B holds knowledge + beliefs + percepts + mailbox (bel/percept
    queries run there) and G holds a copy of the knowledge plus the goal bases. A goal's facts
    are stored as '$gf'(Id, Fact) in G; every predicate that may occur in a goal gets a
    forwarding clause in G that answers from the goal selected by the backtrackable global
    variable '$ga_g'. So goal(Phi) is "Phi follows from knowledge + that ONE goal".
    Python (goalagent/kb/engine.py, mentalstate.py) calls only the exported predicates below.
*/
:- module(ga_kb, []).

:- set_prolog_flag(generate_debug_info, false).

:- initialization(( nb_setval('$ga_g', none),
                     nb_setval('$ga_pending', none),
                     nb_setval('$ga_recheck', false),
                     nb_setval('$ga_warnings', []) )).

%   Agent texts are read with SWI's operators except the prefix operator `table` (tabling
%   directives), so that the everyday atom `table` (blocks worlds: `Y \= table, ...`) reads
%   as an atom, and with `not` as a prefix operator like `\+` (fy 900), as GOAL's Prolog
%   read it, so that `not (p)` and `not p` mean not(p) (SWI 9 rejects `not (p)`).
%   Plain texts are read in module ga_read, agent texts in the agent's modules.

:- set_module(ga_read:base(system)).
:- op(0, fx, ga_read:table).
:- op(900, fy, ga_read:not).

hide_operators(M) :-
    op(0, fx, M:table),
    op(900, fy, M:not).

		 /*******************************
		 *          READING TEXT        *
		 *******************************/

%!  read_text(+Text, +Module, -Term, -Bindings) is det.
%   Reads exactly one term from Text (no final '.') with the operators of Module.

read_text(Text, Module, Term, Bindings) :-
    string_concat(Text, "\n. ", Full),
    setup_call_cleanup(
        open_string(Full, Stream),
        read_one(Stream, Module, Term, Bindings),
        close(Stream)).

read_one(Stream, Module, Term, Bindings) :-
    read_term(Stream, Term,
              [variable_names(Bindings), syntax_errors(error), module(Module)]),
    (   Term == end_of_file
    ->  Char = 0,
        throw(error(syntax_error(end_of_file), exact(Char)))
    ;   true
    ),
    read_term(Stream, Rest, [syntax_errors(error), term_position(RestPos)]),
    (   Rest == end_of_file
    ->  true
    ;   stream_position_data(char_count, RestPos, RestChar),
        throw(error(syntax_error(one_term_expected), exact(RestChar)))
    ).

%!  check(+Text, +Kind, -Result) is det.
%   Result = ok(Names) or syntax(Message, CharOffset); Kind is clause or query.

check(Text, Kind, Result) :-
    catch(check_(Text, Kind, Result), E, syntax_result(E, Text, Result)).

check_(Text, Kind, ok(Names)) :-
    read_text(Text, ga_read, Term, Bindings),
    (   Kind == clause, \+ callable_clause(Term)
    ->  throw(error(syntax_error(not_a_clause), exact(0)))
    ;   true
    ),
    binding_names(Bindings, Names).

callable_clause(Term) :- var(Term), !, fail.
callable_clause((:- _)) :- !.
callable_clause((Head :- _)) :- !, callable(Head).
callable_clause((Head --> _)) :- !, callable(Head).
callable_clause(Term) :- callable(Term).

binding_names(Bindings, Names) :-
    findall(Name, member(Name=_, Bindings), Names).

syntax_result(error(syntax_error(What), Context), Text, syntax(Message, Offset)) :-
    !,
    syntax_message(What, Message),
    error_offset(What, Context, Text, Offset).
syntax_result(E, _, syntax(Message, 0)) :-
    error_message(E, Message).

%!  error_offset(+What, +Context, +Text, -Offset) is det.
%   The offending character. SWI's reader reports the end of the last good token (or the
%   start of the text when the error is at the first token); quotes left open are
%   reported at the start of the clause, so point at the last such quote instead.

error_offset(_, exact(Offset), _, Offset) :- !.
error_offset(end_of_file_in_quoted(Quote), _, Text, Offset) :-
    atom_string(Quote, Q),
    findall(B, sub_string(Text, B, _, _, Q), Bs),
    last(Bs, Offset),
    !.
error_offset(_, Context, Text, Offset) :-
    context_offset(Context, Reported),
    string_length(Text, Length),
    R is min(Reported, Length),
    sub_string(Text, 0, R, _, Before),
    (   split_string(Before, "", " \t\r\n", [""])
    ->  P0 = R
    ;   P0 is R + 1
    ),
    skip_blanks(Text, Length, P0, P),
    Offset is min(P, Length).

skip_blanks(Text, Length, P0, P) :-
    (   P0 < Length,
        sub_string(Text, P0, 1, _, C),
        split_string(C, "", " \t\r\n", [""])
    ->  P1 is P0 + 1,
        skip_blanks(Text, Length, P1, P)
    ;   P = P0
    ).

context_offset(stream(_, _, _, Char), Char) :- integer(Char), !.
context_offset(string(_, Char), Char) :- integer(Char), !.
context_offset(_, 0).

syntax_message(one_term_expected, "end of clause expected (one term only)") :- !.
syntax_message(end_of_file, "end_of_file marks the end of a file: not a term here") :- !.
syntax_message(not_a_clause, "not a clause: a fact, rule or directive was expected") :- !.
syntax_message(What, Message) :-
    catch(( '$messages':translate_message(error(syntax_error(What), _), Lines, []),
            lines_string(Lines, Message0),
            drop_prefix("Syntax error: ", Message0, Message)
          ), _, fail),
    !.
syntax_message(What, Message) :-
    format(string(Message), "~w", [What]).

drop_prefix(Prefix, String, Rest) :-
    (   string_concat(Prefix, Rest0, String)
    ->  Rest = Rest0
    ;   Rest = String
    ).

%!  parse(+Text, -Term) is det.
%   Term with every named variable V bound to '$ga_var'(Name) (Python makes it a Var).

parse(Text, Term) :-
    read_text(Text, ga_read, Term, Bindings),
    maplist(name_var, Bindings).

name_var(Name=Var) :- Var = '$ga_var'(Name).

%!  write_text(+Term, +Quoted, -String) is det.
%   Term as write/1 (Quoted = false) or writeq/1 shows it, with ga_read's operators.

write_text(Term, Quoted, String) :-
    with_output_to(string(String),
                   write_term(Term, [quoted(Quoted), module(ga_read), numbervars(true),
                                     portray(false), spacing(standard)])).

		 /*******************************
		 *            ERRORS            *
		 *******************************/

%!  error_message(+Error, -Message) is det.
%   A readable one-line message for Error, without agent-module qualifications.

error_message(ga_error(Message), Message) :- !.
error_message(E, Message) :-
    E \= error(_, _),
    !,
    strip_agent_modules(E, E1),
    format(string(Message), "Unhandled exception: ~q", [E1]).
error_message(E0, Message) :-
    strip_agent_modules(E0, E1),
    drop_useless_context(E1, E),
    catch(( '$messages':translate_message(E, Lines, []),
            lines_string(Lines, Message0)
          ), _, fail),
    Message0 \== "",
    !,
    Message = Message0.
error_message(E, Message) :-
    format(string(Message), "~q", [E]).

lines_string(Lines, String) :-
    with_output_to(string(S0), print_message_lines(current_output, '', Lines)),
    split_string(S0, "\n", " \t", Parts0),
    exclude(==(""), Parts0, Parts),
    atomic_list_concat(Parts, ' ', Atom),
    atom_string(Atom, String).

strip_agent_modules(T, T) :- var(T), !.
strip_agent_modules(M:T0, T) :-
    atom(M), agent_module(M), !,
    strip_agent_modules(T0, T).
strip_agent_modules(T0, T) :-
    compound(T0), !,
    compound_name_arguments(T0, N, A0),
    maplist(strip_agent_modules, A0, A),
    compound_name_arguments(T, N, A).
strip_agent_modules(T, T).

agent_module(M) :- sub_atom(M, 0, _, _, 'ga_').

drop_useless_context(error(Formal, context(Pred, Msg)), error(Formal, context(_, Msg))) :-
    (   Formal = existence_error(procedure, _)
    ->  true
    ;   nonvar(Pred),
        ( Pred = _:N/_ ; Pred = N/_ ),
        atom(N),
        ( sub_atom(N, 0, _, _, '$') ; sub_atom(N, 0, _, _, '<') ; N == catch ; N == call )
    ),
    !.
drop_useless_context(E, E).

		 /*******************************
		 *      CREATING / LOADING      *
		 *******************************/

%!  new_agent(+B, +G) is det.
%   Creates the belief module B and the goal module G (both based on system only).

new_agent(B, G) :-
    forall(member(M, [B, G]),
           ( set_module(M:class(temporary)),
             set_module(M:base(system)),
             hide_operators(M),
             forall(member(PI, [percept/1, received/2, sent/2, me/1, agent/1]),
                    dynamic(M:PI))
           )),
    dynamic(B:('$kpred'/1, '$ga_dir'/1, '$ga_pre'/3)),
    assertz(B:'$ga_gm'(G)),
    dynamic(G:('$gf'/2, '$goal'/2, '$top'/1, '$fwd'/1)),
    assertz(G:'$top'(0)).

%!  destroy(+B, +G) is det.
destroy(B, G) :-
    '$destroy_module'(B),
    '$destroy_module'(G).

%!  load(+B, +G, +Items, -Result) is det.
%   Items: list of k(Text) (knowledge) and b(Text) (belief) clauses, loaded in order.
%   Result = ok or error(Index, Message) for the first clause that fails (0-based).

load(B, G, Items, Result) :-
    load_(Items, 0, B, G, Result).

load_([], _, _, _, ok).
load_([Item|Items], I, B, G, Result) :-
    (   catch(load_item(Item, B, G), E, true)
    ->  (   var(E)
        ->  I1 is I + 1,
            load_(Items, I1, B, G, Result)
        ;   E = error(syntax_error(What), Context)
        ->  syntax_message(What, Msg0),
            arg(1, Item, Text),
            error_offset(What, Context, Text, Offset),
            format(string(Msg), "syntax error: ~w (at character ~w)", [Msg0, Offset]),
            Result = error(I, Msg)
        ;   error_message(E, Msg),
            Result = error(I, Msg)
        )
    ;   Result = error(I, "directive failed")
    ).

load_item(Item, B, G) :-
    Item =.. [Kind, Text],
    read_text(Text, B, Term, _),
    load_term(Term, Kind, B, G).

load_term((:- Directive), Kind, B, G) :- !,
    directive(Directive, Kind, B, G).
load_term((Head --> Body), Kind, B, G) :- !,
    dcg_translate_rule((Head --> Body), Clause),
    load_term(Clause, Kind, B, G).
load_term(Clause, Kind, B, G) :-
    assertz(B:Clause),
    clause_head(Clause, Head),
    (   Kind == k
    ->  assertz(G:Clause),
        functor(Head, N, A),
        (   B:'$kpred'(N/A)
        ->  true
        ;   assertz(B:'$kpred'(N/A))
        )
    ;   ensure_dynamic(G, Head)
    ).

clause_head((Head :- _), Head) :- !.
clause_head(Head, Head).

directive(dynamic(Spec), _, B, G) :- !,
    dynamic(B:Spec),
    dynamic(G:Spec).
directive(discontiguous(_), _, _, _) :- !.
directive(op(Priority, Type, Names), _, B, G) :- !,
    forall(member(M, [B, G]),
           ( qualify_op_names(Names, M, Qualified),
             op(Priority, Type, Qualified) )).
directive(Directive, Kind, B, G) :-
    once(B:Directive),
    (   Kind == k, load_directive(Directive)
    ->  once(G:Directive)
    ;   true
    ).

load_directive(use_module(_)).
load_directive(use_module(_, _)).
load_directive(ensure_loaded(_)).

%   op/3 acts on the module named in the operator (default: user), so qualify every name.
qualify_op_names(Names, M, Qualified) :-
    (   is_list(Names)
    ->  maplist(qualify_op_name(M), Names, Qualified)
    ;   qualify_op_name(M, Names, Qualified)
    ).

qualify_op_name(_, Name, Name) :- Name = _:_, !.
qualify_op_name(M, Name, M:Name).

%!  ensure_dynamic(+Module, +Head) is det.
%   Declares Head's predicate dynamic in Module unless it is defined there already.

ensure_dynamic(M, Head) :-
    (   current_predicate(_, M:Head)
    ->  true
    ;   predicate_property(M:Head, defined)
    ->  true
    ;   functor(Head, N, A),
        dynamic(M:N/A)
    ).

%!  declare(+B, +G, +Formulas) is det.
%   Every predicate in the conjunctions Formulas (also under not/1) becomes queryable
%   (dynamic if undefined) in both modules.

declare(B, G, Formulas) :-
    forall(( member(Formula, Formulas),
             catch(conjuncts(Formula, Lits), _, fail),
             member(Lit, Lits),
             positive(Lit, H),
             fact_like(H) ),
           ( ensure_dynamic(B, H), ensure_dynamic(G, H) )).

positive(Lit, Lit) :- var(Lit), !.
positive(not(Lit), Lit) :- !.
positive(\+ Lit, Lit) :- !.
positive(Lit, Lit).

%!  declare_goal(+B, +G, +Facts) is det.
%   As declare/3, and the predicates of Facts can be goal facts (forwarders in G).

declare_goal(B, G, Facts) :-
    forall(( member(F, Facts), fact_like(F) ),
           ( ensure_dynamic(B, F), forwarder(G, F) )).

fact_like(H) :-
    callable(H),
    \+ control(H).

control((_, _)).
control((_ ; _)).
control((_ -> _)).
control((_ *-> _)).
control(\+ _).
control(not(_)).
control(true).
control(_:_).

%!  forwarder(+G, +Head) is det.
%   Makes Head's predicate in G answer from the goal selected by '$ga_g'.

forwarder(G, Head) :-
    functor(Head, N, A),
    (   G:'$fwd'(N/A)
    ->  true
    ;   predicate_property(G:Head, defined),
        \+ predicate_property(G:Head, dynamic)
    ->  true                        % a built-in: it can never be a goal fact
    ;   functor(Gen, N, A),
        dynamic(G:N/A),
        assertz(G:(Gen :- b_getval('$ga_g', Id), '$gf'(Id, Gen))),
        assertz(G:'$fwd'(N/A))
    ).

		 /*******************************
		 *        CONDITIONS            *
		 *******************************/

%!  compile(+B, +G, +Name, +Text, -Names) is det.
%   Text is a conjunction of '$bel'(Q), '$goal'(Q), '$agoal'(Q), '$goala'(Q),
%   '$percept'(Q), true and \+ (...); asserts B:Name(Vars...) :- Body and returns the
%   variable names in order of first appearance (= the arguments). Each goal literal becomes
%   an auxiliary clause Name_I in G, called through the module name stored in B (a clause of
%   one temporary module may not name another one).

compile(B, G, Name, Text, Names) :-
    read_text(Text, B, Cond, Bindings),
    binding_names(Bindings, Names),
    maplist(arg(2), Bindings, Vars),
    translate(Cond, Name, Body, 0, _, Auxes, []),
    forall(member(Aux, Auxes), assertz(G:Aux)),
    Head =.. [Name|Vars],
    assertz(B:(Head :- Body)).

translate((A0, B0), Name, (A, B), N0, N, Aux0, Aux) :- !,
    translate(A0, Name, A, N0, N1, Aux0, Aux1),
    translate(B0, Name, B, N1, N, Aux1, Aux).
translate(\+ A0, Name, \+ A, N0, N, Aux0, Aux) :- !,
    translate(A0, Name, A, N0, N, Aux0, Aux).
translate(true, _, true, N, N, Aux, Aux) :- !.
translate('$bel'(Q0), _, Q, N, N, Aux, Aux) :- !,
    local_cut(Q0, Q).
translate('$goal'(Q), Name, Call, N0, N, [Clause|Aux], Aux) :- !,
    in_goal(Q, Name, N0, Call, Clause),
    N is N0 + 1.
translate('$agoal'(Q), Name, (Call, \+ Q), N0, N, [Clause|Aux], Aux) :- !,
    in_goal(Q, Name, N0, Call, Clause),
    N is N0 + 1.
translate('$goala'(Q), Name, (Call, LocalQ), N0, N, [Clause|Aux], Aux) :- !,
    in_goal(Q, Name, N0, Call, Clause),
    local_cut(Q, LocalQ),
    N is N0 + 1.
translate('$percept'(Q), _, Body, N, N, Aux, Aux) :-
    percept_body(Q, Body).

in_goal(Q, Name, I, ('$ga_gm'(G), G:AuxHead),
        (AuxHead :- '$top'(Base), '$goal'(Base, Id), b_setval('$ga_g', Id), LocalQ)) :-
    local_cut(Q, LocalQ),
    format(atom(AuxName), '~w_~w', [Name, I]),
    term_variables(Q, Vars),
    AuxHead =.. [AuxName|Vars].

%   A cut in a query cuts that query only, as if each literal were its own Prolog query.
local_cut(Q, Local) :-
    (   has_cut(Q)
    ->  Local = call(Q)
    ;   Local = Q
    ).

has_cut(Q) :- var(Q), !, fail.
has_cut(!).
has_cut((A, B)) :- ( has_cut(A) -> true ; has_cut(B) ).
has_cut((A ; B)) :- ( has_cut(A) -> true ; has_cut(B) ).
has_cut((A -> B)) :- ( has_cut(A) -> true ; has_cut(B) ).
has_cut((A *-> B)) :- ( has_cut(A) -> true ; has_cut(B) ).

percept_body(Q, percept(Q)) :- var(Q), !.
percept_body((A0, B0), (A, B)) :- !,
    percept_body(A0, A),
    percept_body(B0, B).
percept_body(Q, percept(Q)).

		 /*******************************
		 *            RULES             *
		 *******************************/

%!  compile_rule(+B, +Kind, +Name, +CondName, +CondArity, +Text, -Names) is det.
%   Text is '$rule'(Cond, Actions): a condition compiled in every agent that uses the rule
%   as CondName/CondArity and the list of the rule's leading actions done in Prolog
%   (insert/delete/adopt/drop of a formula, do(Action) for a user action, see
%   declare_actions/2, and last env(Action) for one whose precondition only is checked
%   here, see perform/5), read with B's operators so that they share variables. Asserts
%   ga_rules:Name(Agent, Vars..., Recheck, Total, Kept, Warnings) :- fire(...) (see
%   fire/9), Vars being the named variables of Text in order of first appearance (the
%   condition's first). The clause serves every agent (Agent is its belief module): agents
%   share their rules' code, as they share their conditions' names.

compile_rule(B, Kind, Name, CondName, CondArity, Text, Names) :-
    read_text(Text, B, '$rule'(_, Actions), Bindings),
    binding_names(Bindings, Names),
    maplist(arg(2), Bindings, Vars),
    length(CondVars, CondArity),
    append(CondVars, _, Vars),
    Cond =.. [CondName|CondVars],
    append([Agent|Vars], [Recheck, Total, Kept, Warnings], Args),
    Head =.. [Name|Args],
    assertz(ga_rules:(Head :- ga_kb:fire(Kind, Agent, Cond, Vars, Actions, Recheck, Total,
                                         Kept, Warnings))).

%!  fire(+Kind, +B, +Cond, +Vars, +Actions, +Recheck, -Total, -Kept, -Warnings) is det.
%   Applies a rule whose actions start with Actions (built in, done here): for the first
%   instantiation of Cond whose first action is enabled (Kind = if) or for every one
%   (Kind = forall), performs the actions in order until one is not enabled, with blind
%   commitment after each (a full check after the first one when Recheck is true: percepts
%   or messages changed since the last check). Kept is k(Dones, Values, Pending): per
%   firing, how many actions were performed and the values of Vars, and the environment
%   action left for Python (see perform/5) or none; Total is the number of actions
%   performed, the pending one included (what Python reads at once). Warnings:
%   see warning/2 (an action that
%   raised an error is not enabled). Instantiations are
%   all computed before any action, so the condition sees the state of the rule's start.

fire(Kind, B, Cond, Vars, Actions, Recheck, Total, Kept, Warnings) :-
    findall(Vars, B:Cond, Solutions),
    (   Solutions == []
    ->  Total = 0, Kept = k([], [], none), Warnings = []
    ;   B:'$ga_gm'(G),
        nb_setval('$ga_recheck', Recheck),
        nb_setval('$ga_pending', none),
        fire_(Kind, Solutions, Vars, Actions, B, G, Dones, Values),
        sum_list(Dones, Total),
        nb_getval('$ga_pending', Pending),
        Kept = k(Dones, Values, Pending),
        take_warnings(Warnings)
    ).

fire_(if, Solutions, Vars, Actions, B, G, Dones, Values) :-
    (   member(Vars, Solutions),
        perform(Actions, 0, B, G, Done),
        Done > 0
    ->  Dones = [Done],
        Values = [Vars]
    ;   Dones = [],
        Values = []
    ).
fire_(forall, Solutions, Vars, Actions, B, G, Dones, Values) :-
    findall(Done-Vars,
            ( member(Vars, Solutions),
              perform(Actions, 0, B, G, Done),
              Done > 0 ),
            Pairs),
    pairs_keys_values(Pairs, Dones, Values).

%!  declare_actions(+B, +Specs) is det.
%   Specs: list of spec(Index, Text), Text being '$spec'(Action, Pre, Post) for one
%   actionspec (Index: its place in the program). Asserts, in order,
%   B:'$ga_pre'(Action, Post, Index) :- Pre, so that the first clause whose Action unifies
%   and whose Pre holds gives the action's postcondition (see action/3). A Prolog error in
%   Pre is a warning p(Index, Message) and that spec does not apply.

declare_actions(B, Specs) :-
    forall(member(spec(Index, Text), Specs),
           ( read_text(Text, B, '$spec'(Action, Pre, Post), _),
             local_cut(Pre, Body),
             assertz(B:('$ga_pre'(Action, Post, Index) :-
                           catch(Body, E, ( ga_kb:push_warning(p(Index, E)), fail )))) )).

%!  compile_pass(+Name, +Stop, +Rules) is det.
%   Asserts ga_rules:Name(Agent, Order, Recheck, Total, Kept, Warnings) :- pass(...)
%   (see pass/7): one call applies the compiled rules Rules (a list of Name/Arity of
%   compile_rule/7 clauses, called without given bindings) in their order (Order = []) or
%   in the order of the 0-based indices in Order, stopping after the first that fires if
%   Stop is true. Shared by every agent, as the rules are.

compile_pass(Name, Stop, Rules) :-
    maplist(rule_call(Agent), Rules, Calls),
    Head =.. [Name, Agent, Order, Recheck, Total, k(Dones, Values), Warnings],
    assertz(ga_rules:(Head :- ga_kb:ordered(Order, Calls, Ordered),
                              ga_kb:pass(Ordered, 0, Stop, Recheck, Total, Dones, Values,
                                         Warnings))).

ordered([], Calls, Calls) :- !.
ordered(Order, Calls, Ordered) :-
    maplist(nth_call(Calls), Order, Ordered).

nth_call(Calls, Index, Call) :-
    nth0(Index, Calls, Call).

rule_call(Agent, Name/Arity, rule(Goal, Recheck, Total, Kept, Warnings)) :-
    functor(Goal, Name, Arity),
    Goal =.. [Name, Agent|Args],
    append(_, [Recheck, Total, Kept, Warnings], Args),
    !.

%!  pass(+Rules, +Index, +Stop, +Recheck, -Total, -Dones, -Values, -Warnings) is det.
%   Total: the number of actions performed. Dones lists, per rule tried in the order
%   tried, its firings' numbers of actions (as fire/9 gives them) followed by 0; Values
%   has the firings' values per rule; Warnings lists r(Rule, Warning): the warnings of
%   fire/9, and c(Message) for a condition that raised an error (such a rule is not
%   applicable).

pass([], _, _, _, 0, [], [], []).
pass([rule(Goal, Recheck, T, k(D, V, _), W)|Rules], I, Stop, Recheck, Total, Dones0,
     [V|Values], Warnings) :-
    (   catch(ga_rules:Goal, E, true)
    ->  (   var(E)
        ->  rule_warnings(W, I, Warnings, Warnings1)
        ;   T = 0, D = [], V = [],
            error_message(E, Message),
            Warnings = [r(I, c(Message))|Warnings1]
        )
    ;   T = 0, D = [], V = [], Warnings = Warnings1
    ),
    append(D, [0|Dones], Dones0),
    (   Stop == true, T > 0
    ->  Total = T, Dones = [], Values = [], Warnings1 = []
    ;   nb_getval('$ga_recheck', Recheck1),
        I1 is I + 1,
        pass(Rules, I1, Stop, Recheck1, Total1, Dones, Values, Warnings1),
        Total is T + Total1
    ).

rule_warnings([], _, Warnings, Warnings).
rule_warnings([W|Ws], I, [r(I, W)|Warnings], Rest) :-
    rule_warnings(Ws, I, Warnings, Rest).

%   perform(+Actions, +Index, +B, +G, -Done): the actions in order up to the first one that
%   is not enabled; Done is the index of that one (or the length of Actions). A last action
%   env(Action) is one for the environment: only its precondition is checked here, and
%   '$ga_pending' gets p(Action, Post, Spec) for Python to perform it and apply Post.
perform([], Index, _, _, Index).
perform([env(Action)], Index, B, _, Done) :- !,
    (   catch(env_action(Action, B), E, (warning(Index, E), fail))
    ->  Done is Index + 1
    ;   Done = Index
    ).
perform([Action|Actions], Index, B, G, Done) :-
    (   catch(action(Action, B, G), E, (warning(Index, E), fail))
    ->  after_action(B, G),
        Next is Index + 1,
        perform(Actions, Next, B, G, Done)
    ;   Done = Index
    ).

env_action(Action, B) :-
    B:'$ga_pre'(Action, Post, Spec),
    !,
    (   ground(Action)
    ->  nb_setval('$ga_pending', p(Action, Post, Spec))
    ;   throw(ga_open(Action))
    ).

action(insert(F), B, G) :- update(B, G, insert, F, _, _, _).
action(delete(F), B, G) :- update(B, G, delete, F, _, _, _).
action(adopt(F), B, G) :- adopt(B, G, F, adopted).
action(drop(F), B, G) :- drop(B, G, F, _).
action(do(Action), B, G) :-
    B:'$ga_pre'(Action, Post, _),
    !,
    (   ground(Action)
    ->  update(B, G, insert, Post, _, _, _)
    ;   throw(ga_open(Action))
    ).

%   Blind commitment after an action: insert/delete checked what they changed (update/7);
%   the first action after new percepts or messages checks every goal.
after_action(B, G) :-
    (   nb_getval('$ga_recheck', true)
    ->  nb_setval('$ga_recheck', false),
        blind_commitment(B, G, _)
    ;   true
    ).

%   Warnings: w(Action, Message) for an action that raised an error, o(Action, Term) for a
%   user action not closed after its precondition, p(Spec, Message) for a precondition that
%   raised an error.
warning(Index, ga_open(Action)) :- !,
    push_warning(o(Index, Action)).
warning(Index, E) :-
    push_warning(w(Index, E)).

push_warning(Warning0) :-
    (   arg(2, Warning0, E), Warning0 \= o(_, _)
    ->  error_message(E, Message),
        setarg(2, Warning0, Message)
    ;   true
    ),
    nb_getval('$ga_warnings', W0),
    nb_setval('$ga_warnings', [Warning0|W0]).

take_warnings(Warnings) :-
    nb_getval('$ga_warnings', W0),
    (   W0 == []
    ->  Warnings = []
    ;   nb_setval('$ga_warnings', []),
        reverse(W0, Warnings)
    ).

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
    ->  Changed1 = true
    ;   Changed1 = Changed0
    ),
    delete_facts(Facts, B, More, Changed1, Changed).

add_facts([], _, _, [], Changed, Changed).
add_facts([Fact|Facts], B, G, [Added|More], Changed0, Changed) :-
    add_fact(B, G, Fact, Added),
    (   Added == 1
    ->  Changed1 = true
    ;   Changed1 = Changed0
    ),
    add_facts(Facts, B, G, More, Changed1, Changed).

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
        maplist(remove_goal(G), Ids, Removed)
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
    forall(member(Facts, FactLists), add_goal(G, Base, Facts)).

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
    forall(member(P, Percepts), assertz(B:percept(P))).

%!  percepts(+B, -Percepts) is det.
percepts(B, Percepts) :-
    findall(P, B:percept(P), Percepts).

%!  add_once(+B, +Fact, -Added) is det.
%   Asserts Fact unless already there; Added is true or false.

add_once(B, Fact, Added) :-
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
    forall(member(A, Agents), assertz(B:agent(A))).

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
    assertz(B:(agent(A) :- '$ga_dir'(D), D:agent(A))).

%!  destroy_directory(+S) is det.
destroy_directory(S) :-
    '$destroy_module'(S).
