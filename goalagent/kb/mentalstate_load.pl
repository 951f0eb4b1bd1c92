
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
    dynamic(B:('$kpred'/1, '$ga_dir'/1, '$ga_pre'/4, '$ga_pre_body'/3, '$ga_wk'/2,
               '$ga_confine'/1, '$ga_limits'/2, '$ga_key'/2)),
    assertz(B:'$ga_gm'(G)),
    recheck(B),
    dynamic(G:('$gf'/3, '$goal'/3, '$top'/1, '$fwd'/1, '$rule_inserted'/0)),
    assertz(G:'$top'(0)),
    nb_setval(G, []).

%!  destroy(+B, +G) is det.
destroy(B, G) :-
    retractall('$ga_conditions'(B, _, _)),
    ga_confine:forget_keys(B),
    nb_delete(B),
    nb_delete(G),
    '$destroy_module'(B),
    '$destroy_module'(G).

%!  load(+B, +G, +Items, +Sandbox, +RunsCode, -Result) is det.
%   Items: list of k(Text) (knowledge) and b(Text) (belief) clauses, loaded in order, each
%   prepared by confine.pl (checked, calls known only at run time wrapped; Sandbox: true
%   or false, kept for what the agent runs later). RunsCode = false (goalagent check): no
%   directive runs but declarations, operators and library loads, so nothing the agent
%   wrote is executed (the others are still checked). Result = ok or error(Index, Message)
%   for the first clause that fails (0-based); nothing of a program with an error runs.

load(B, G, Items, Sandbox, RunsCode, Result) :-
    (   Sandbox == true -> ga_confine:load_sandbox ; true ),
    assertz(B:'$ga_confine'(Sandbox)),
    maplist(read_item(B), Items, Read),
    program_heads(Read, Own),
    load_(Items, Read, 0, B, G, c(B, Sandbox, Own), RunsCode, Result).

%   read_item(+B, +Item, -Read): the item's text read before anything is loaded, t(Term),
%   or unread when it does not read yet (its operators come with a directive); load_/8
%   uses the term while no directive has run (nothing else changes how a text reads).
read_item(B, Item, Read) :-
    arg(1, Item, Text),
    (   catch(read_text(Text, B, Term, _), _, fail)
    ->  Read = t(Term)
    ;   Read = unread
    ).

%   program_heads(+Read, -Own): the Name/Arity of every clause, grammar rule and
%   dynamic declaration of the program, read before any is loaded: a clause may call a
%   predicate of the agent's own that is written further on and named like a built-in
%   confine.pl refuses (told/0, append/1). A text that only reads once its directives
%   have run (its operators) is left out; it is read, and reported, when it is loaded.
program_heads(Read, Own) :-
    findall(Name/Arity,
            ( member(t(Term), Read),
              term_head(Term, Name, Arity) ),
            Own0),
    sort(Own0, Own).

term_head(Var, _, _) :- var(Var), !, fail.
term_head((:- dynamic(Specs)), Name, Arity) :- !,
    declared(Specs, Name, Arity).
term_head((:- _), _, _) :- !, fail.
term_head((Head, _ --> _), Name, Arity) :- !,
    term_head((Head --> true), Name, Arity).
term_head((Head --> _), Name, Arity) :- !,
    callable(Head),
    functor(Head, Name, Arity0),
    Arity is Arity0 + 2.
term_head((Head :- _), Name, Arity) :- !,
    callable(Head),
    functor(Head, Name, Arity).
term_head(Head, Name, Arity) :-
    callable(Head),
    functor(Head, Name, Arity).

declared(Specs, Name, Arity) :-
    nonvar(Specs),
    (   ( Specs = [_|_] ; Specs = (_, _) )
    ->  ( Specs = [S|Rest] ; Specs = (S, Rest) ),
        ( declared(S, Name, Arity) ; declared(Rest, Name, Arity) )
    ;   Specs = Name/Arity
    ;   Specs = Name//Arity0, integer(Arity0), Arity is Arity0 + 2
    ).

load_([], _, _, _, _, _, _, ok).
load_([Item|Items], [Read|Reads], I, B, G, Ctx, RunsCode, Result) :-
    Item =.. [Kind, Text],
    (   catch(( read_once(Read, Text, B, Term),  % after earlier directives (operators)
                load_term(Term, Kind, B, G, Ctx, RunsCode) ), E, true)
    ->  (   var(E)
        ->  I1 is I + 1,
            (   Term = (:- _)                   % a directive may change how texts read
            ->  maplist(=(unread), Reads0),
                same_length(Reads, Reads0)
            ;   Reads0 = Reads
            ),
            load_(Items, Reads0, I1, B, G, Ctx, RunsCode, Result)
        ;   load_error(E, I, Text, Result)
        )
    ;   Result = error(I, "directive failed")
    ).

read_once(t(Term), _, _, Term) :- !.
read_once(unread, Text, B, Term) :-
    read_text(Text, B, Term, _).

load_error(error(syntax_error(What), Context), I, Text, error(I, Msg)) :- !,
    syntax_message(What, Msg0),
    error_offset(What, Context, Text, Offset),
    format(string(Msg), "syntax error: ~w (at character ~w)", [Msg0, Offset]).
load_error(ga_refused(Why), I, _, error(I, Msg)) :- !,
    format(string(Msg), "refused: ~w", [Why]).
load_error(E, I, _, error(I, Msg)) :-
    error_message(E, Msg).

load_term((:- Directive), Kind, B, G, Ctx, RunsCode) :- !,
    directive(Directive, Kind, B, G, Ctx, RunsCode).
load_term((Head --> Body), Kind, B, G, Ctx, RunsCode) :- !,
    dcg_translate_rule((Head --> Body), Clause),
    load_term(Clause, Kind, B, G, Ctx, RunsCode).
load_term(Clause0, Kind, B, G, Ctx, _) :-
    ga_confine:prepare_clause(Clause0, Ctx, Clause1),
    ga_sizes:inline_clause(Clause1, Clause),
    clause_head(Clause, Head),
    make_own(B, Head),
    loaded_assertz(B, Clause),
    (   Kind == k
    ->  make_own(G, Head),
        loaded_assertz(G, Clause),
        functor(Head, N, A),
        (   B:'$kpred'(N/A)
        ->  true
        ;   loaded_assertz(B, '$kpred'(N/A))
        )
    ;   ensure_dynamic(G, Head)
    ).

%   (the program's own clauses, made by ga_sizes:inline_clause/2: their arithmetic inline)
loaded_assertz(M, Clause) :-
    ga_sizes:with_optimise(ga_kb:assertz(M:Clause)),
    note_loaded(assert(M, Clause)).

clause_head((Head :- _), Head) :- !.
clause_head(Head, Head).

directive(Directive, Kind, B, G, Ctx, RunsCode) :-
    ga_confine:prepare_directive(Directive, Ctx, Prepared),
    directive_(Prepared, Kind, B, G, RunsCode).

directive_(dynamic(Spec), _, B, G, _) :- !,
    dynamic(B:Spec),
    dynamic(G:Spec).
directive_(discontiguous(_), _, _, _, _) :- !.
directive_(op(Priority, Type, Names), _, B, G, _) :- !,
    forall(member(M, [B, G]),
           ( qualify_op_names(Names, M, Qualified),
             op(Priority, Type, Qualified) )).
directive_(Directive, Kind, B, G, false) :- !,  % checked, not run; a library load (of
    (   load_directive(Directive)               % SWI-Prolog's code, not the agent's, and
    ->  directive_(Directive, Kind, B, G, true) % allowed by prepare_directive/3) is made
    ;   true
    ).
directive_(Directive, Kind, B, G, true) :-
    B:'$ga_limits'(MaxInferences, _),           % a directive that runs away (:- p, p :- p)
    call_with_inference_limit(once(B:Directive), MaxInferences, Result),   % is the
    (   Result == inference_limit_exceeded      % program's located error
    ->  throw(ga_limit(inferences(MaxInferences)))
    ;   true
    ),
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
%   Declares Head's predicate dynamic in Module unless the agent defines it there already;
%   it is the agent's own even where SWI-Prolog has a predicate of that name (make_own/2).

ensure_dynamic(M, Head) :-
    (   predicate_property(M:Head, implementation_module(M)),
        predicate_property(M:Head, defined)
    ->  true
    ;   make_own(M, Head),
        functor(Head, N, A),
        dynamic(M:N/A),
        note_loaded(dynamic(M, N/A))
    ).

%!  make_own(+M, +Head) is det.
%   Head's predicate can be the agent's own in M although SWI-Prolog has one of that name:
%   a library's (index/1) is shadowed by defining it in M, a system predicate (told/0) is
%   redefined there; the agent's definitions win, as in GOAL. An ISO built-in (atom/1,
%   is/2, ...) cannot be: ga_error. (implementation_module/1 is asked because, unlike other
%   properties, it does not link M to a library's predicate.)

make_own(M, Head) :-
    predicate_property(M:Head, implementation_module(Impl)),
    (   Impl \== system
    ->  true
    ;   predicate_property(system:Head, iso)
    ->  functor(Head, N, A),
        format(string(Message), "~w/~w is a built-in predicate of ISO Prolog; an agent \c
                                 cannot make it its own (rename it)", [N, A]),
        throw(ga_error(Message))
    ;   redefine_system_predicate(M:Head),
        note_loaded(redefine(M, Head))
    ).

%!  declare(+B, +G, +Formulas, -Result) is det.
%   Every predicate in the conjunctions Formulas (also under not/1) becomes queryable
%   (dynamic if undefined) in both modules, and the agent's own. Result = ok, or
%   error(Index, Message) for the first formula that names an ISO built-in.

declare(B, G, Formulas, Result) :-
    catch(( forall(nth0(Index, Formulas, Formula),
                   catch(declare_formula(B, G, Formula), ga_error(Message),
                         throw(declare_error(Index, Message)))),
            Result = ok ),
          declare_error(Index, Message),
          Result = error(Index, Message)).

declare_formula(B, G, Formula) :-
    forall(( catch(conjuncts(Formula, Lits), _, fail),
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

declare_goal(_, _, []).
declare_goal(B, G, [Fact|Facts]) :-
    (   fact_like(Fact)
    ->  functor(Fact, Name, Arity),
        (   G:'$fwd'(Name/Arity)            % declared before
        ->  true
        ;   ensure_dynamic(B, Fact),
            forwarder(G, Fact)
        )
    ;   true
    ),
    declare_goal(B, G, Facts).

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
%   Makes Head's predicate in G answer from the goal selected by '$ga_g' (an ISO built-in
%   can never be a goal fact).

forwarder(G, Head) :-
    functor(Head, N, A),
    (   G:'$fwd'(N/A)
    ->  true
    ;   predicate_property(system:Head, iso)
    ->  true
    ;   make_own(G, Head),
        functor(Gen, N, A),
        dynamic(G:N/A),
        assertz(G:(Gen :- b_getval('$ga_g', Id), '$gf'(Id, Gen, _))),
        assertz(G:'$fwd'(N/A))
    ).

		 /*******************************
		 *        CONDITIONS            *
		 *******************************/

%!  compile(+B, +G, +Name, +Text, +Confined, -Names) is det.
%   Text is a conjunction of '$bel'(Q), '$goal'(Q), '$agoal'(Q), '$goala'(Q),
%   '$percept'(Q), true and \+ (...); asserts B:Name(Vars...) :- Body and returns the
%   variable names in order of first appearance (= the arguments). Each goal literal becomes
%   an auxiliary clause Name_I in G, called through the module name stored in B (a clause of
%   one temporary module may not name another one). Confined = true (the agent's own
%   conditions): its queries are prepared by confine.pl first; sandbox (what the mind
%   inspector's page writes): prepared so, and in the sandbox whatever the agent's is.

compile(B, G, Name, Text, Confined, Names) :-
    read_text(Text, B, Cond0, Bindings),
    binding_names(Bindings, Names),
    maplist(arg(2), Bindings, Vars),
    (   Confined == true
    ->  ga_confine:prepare_condition(Cond0, B, Cond)
    ;   Confined == sandbox
    ->  ga_confine:prepare_sandboxed_condition(Cond0, B, Cond)
    ;   Cond = Cond0                    % the runtime's own query (API, reports)
    ),
    translate(Cond, Name, Body, 0, _, Auxes0, []),
    Head =.. [Name|Vars],
    (   Confined == true                % the agent's own: its arithmetic inline
    ->  maplist(ga_sizes:inline_clause, Auxes0, Auxes),
        ga_sizes:inline_clause((Head :- Body), Clause),
        ga_sizes:with_optimise(ga_kb:( forall(member(Aux, Auxes), assertz(G:Aux)),
                                       assertz(B:Clause) ))
    ;   forall(member(Aux, Auxes0), assertz(G:Aux)),
        assertz(B:(Head :- Body))
    ).

%!  clone_conditions(+FromB, +FromG, +ToB, +ToG, +Names, -Cloned) is det.
%   Copies the clauses compile/6 made of the conditions Names for the agent of FromB/FromG
%   (and their goal clauses Name_I) to the agent of ToB/ToG, the two module names renamed:
%   what compile/6 makes for another agent of the same program loaded alike, without
%   reading and confining the texts again (launching 10,000 copies of an agent reads each
%   condition once). Cloned = false, and nothing is copied, when a clause names anything
%   else of the first agent's (an own global variable or flag key: confine_keys.pl).

:- dynamic('$ga_conditions'/3).

clone_conditions(FromB, FromG, ToB, ToG, Names, Cloned) :-
    (   '$ga_conditions'(FromB, Names, Found)
    ->  true
    ;   conditions_found(FromB, FromG, Names, Found),
        assertz('$ga_conditions'(FromB, Names, Found))
    ),
    (   Found = found(Clauses, Named)
    ->  Map = [FromB-ToB, FromG-ToG],
        ga_sizes:with_optimise(                 % (as compile/6 asserted them)
            ga_kb:forall(member(M0-Clause0, Clauses),
                   ( (   Named == true
                     ->  renamed(Clause0, Map, Clause)
                     ;   Clause = Clause0
                     ),
                     memberchk(M0-M, Map),
                     assertz(M:Clause) ))),
        Cloned = true
    ;   Cloned = false
    ).

%   conditions_found(+FromB, +FromG, +Names, -Found): found(Clauses, Named), the clauses
%   (Module-Clause) that compile/6 made of the conditions Names for the agent of
%   FromB/FromG and whether any names its modules (to be renamed), or none when one is
%   missing or a clause names anything else of that agent's. Kept for the next agents
%   that copy the same conditions from it ('$ga_conditions'/3, until it is destroyed: the
%   clauses of a condition's name never change).
conditions_found(FromB, FromG, Names, Found) :-
    findall(FromB-Clause, ( member(Name, Names), module_clause(FromB, Name, Clause) ), Own),
    findall(FromG-Clause, ( member(Name, Names), goal_clause(FromG, Name, 0, Clause) ), Goals),
    append(Own, Goals, Clauses),
    sub_atom(FromB, 5, _, 0, Secret),               % ga_b_<secret>, ga_g_<secret>
    length(Names, Count),
    (   length(Own, Count),                         % one clause per condition
        \+ ( sub_term(Text, Clauses), ( atom(Text) ; string(Text) ),
             Text \== FromB, Text \== FromG, sub_atom(Text, _, _, _, Secret) )
    ->  (   sub_term(Text, Clauses), ( Text == FromB ; Text == FromG )
        ->  Found = found(Clauses, true)
        ;   Found = found(Clauses, false)
        )
    ;   Found = none
    ).

module_clause(M, Name, (Head :- Body)) :-
    current_predicate(M:Name/Arity),
    functor(Head, Name, Arity),
    clause(M:Head, Body).

goal_clause(G, Name, I, Clause) :-
    format(atom(Aux), '~w_~w', [Name, I]),
    current_predicate(G:Aux/_),
    (   module_clause(G, Aux, Clause)
    ;   I1 is I + 1,
        goal_clause(G, Name, I1, Clause)
    ).

renamed(Term0, Map, Term) :-
    (   atom(Term0), memberchk(Term0-Term1, Map)
    ->  Term = Term1
    ;   compound(Term0)
    ->  compound_name_arguments(Term0, F, Args0),
        renamed_list(Args0, Map, Args),
        compound_name_arguments(Term, F, Args)
    ;   Term = Term0
    ).

renamed_list([], _, []).
renamed_list([A0|As0], Map, [A|As]) :-
    renamed(A0, Map, A),
    renamed_list(As0, Map, As).

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
        (AuxHead :- '$top'(Base), '$goal'(Base, Id, _), b_setval('$ga_g', Id), LocalQ)) :-
    local_cut(Q, LocalQ),
    format(atom(AuxName), '~w_~w', [Name, I]),
    term_variables(Q, Vars),
    AuxHead =.. [AuxName|Vars].

%   A cut in a query cuts that query only, as if each literal were its own Prolog query.
%   not/1 at a goal position of the query is compiled as \+ (the same negation, one call
%   less).
local_cut(Q0, Local) :-
    inline_not(Q0, Q),
    (   has_cut(Q)
    ->  Local = call(Q)
    ;   Local = Q
    ).

inline_not(Q, Q) :- var(Q), !.
inline_not((A0, B0), (A, B)) :- !, inline_not(A0, A), inline_not(B0, B).
inline_not((A0 ; B0), (A ; B)) :- !, inline_not(A0, A), inline_not(B0, B).
inline_not((A0 -> B0), (A -> B)) :- !, inline_not(A0, A), inline_not(B0, B).
inline_not((A0 *-> B0), (A *-> B)) :- !, inline_not(A0, A), inline_not(B0, B).
inline_not(\+ A0, \+ A) :- !, inline_not(A0, A).
inline_not(not(A0), \+ A) :- !, inline_not(A0, A).
inline_not(Q, Q).

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
