/*  Support predicates for goalagent's mental states and the rule interpreter (loaded once
    per process, as module ga_kb; the parts are included below).

    One agent = two modules: B holds knowledge + beliefs + percepts + mailbox (bel/percept
    queries run there) and G holds a copy of the knowledge plus the goal bases. A goal's
    facts are stored as '$gf'(Id, Fact, WatchKey) in G (see watch/1); every predicate that
    may occur in a goal gets a forwarding clause in G that answers from the goal selected
    by the backtrackable global variable '$ga_g'. So goal(Phi) is "Phi follows from
    knowledge + that ONE goal".
    Python (goalagent/kb/engine.py, mentalstate.py, interpreter.py) calls only the
    predicates documented with %! in these files.

    mentalstate.pl           reading text, error messages
    mentalstate_load.pl      creating and loading agents, compiling conditions
    mentalstate_updates.pl   insert/delete, goals, percepts, messages, agent directories
    rules.pl                 the rule interpreter: compiled rules and module passes
*/
:- module(ga_kb, []).

:- set_prolog_flag(generate_debug_info, false).
%   The interpreter's own arithmetic (journal counts, action indexes, ids: integers it
%   makes itself) compiled inline instead of calls of is/2 and >/2 (this file only).
:- set_prolog_flag(optimise, true).

%   '$ga_g': the goal a goal/1 query reads (see forwarder/2); '$ga_listen': true while the
%   running agent has listeners, so the interpreter reports each step (see tell/1 in
%   rules.pl); '$ga_goal_id': the last goal id given (see add_goal/5); '$ga_max_inferences'
%   and '$ga_unchecked': the running call's inference limit and the goals whose checks
%   failed while check_goals_bounded/4 runs (none otherwise). Each agent's belief
%   module name holds its "recheck" flag (see recheck/1), its goal module name what its
%   goals watch (see watch/1).
:- initialization(( nb_setval('$ga_g', none),
                     nb_setval('$ga_listen', false),
                     nb_setval('$ga_goal_id', 0),
                     nb_setval('$ga_max_inferences', 0),
                     nb_setval('$ga_unchecked', none) )).

:- include(mentalstate_load).
:- include(mentalstate_images).
:- include(mentalstate_updates).
:- include(rules).

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
    ga_guard:check_depth(Text, Term),
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

%   SWI's writer recurses in C once per level; its C-stack guard (on: goalagent/kb/clib.py
%   starts SWI with signal handling) stops a term too deep for the C stack with a
%   resource error, said here in the agent's words.
write_text(Term, Quoted, String) :-
    catch(with_output_to(string(String),
                         write_term(Term, [quoted(Quoted), module(ga_read), numbervars(true),
                                           portray(false), spacing(standard)])),
          error(resource_error(c_stack), _),
          throw(ga_error("a term nested too deeply to write (SWI's writer ran out of C stack)"))).

%   writable(@Term): Term is at most 5,000 deep, short enough to show in a message (a
%   deeper one would fill the screen, or run SWI's writer out of C stack).
writable(Term) :-
    ga_guard:within(Term, 5000).

		 /*******************************
		 *            ERRORS            *
		 *******************************/

%!  error_message(+Error, -Message) is det.
%   A readable one-line message for Error, without agent-module qualifications.

error_message(E, Message) :-
    error_message_(E, Message0),
    shortened(Message0, Message).

%   A message of at most 2,000 characters: an error can carry a huge term (an atom of
%   100 MB made with one format/3 call), and a warning must not print it all.
shortened(Message0, Message) :-
    (   string_length(Message0, Length),
        Length > 2000
    ->  sub_string(Message0, 0, 1000, _, Start),
        format(string(Message), "~s... (~D characters)", [Start, Length])
    ;   Message = Message0
    ).

error_message_(ga_error(Message), Message) :- !.
error_message_(E, Message) :-
    \+ acyclic_term(E), !,
    Message = "an error whose term is cyclic (it contains itself)".
error_message_(E, Message) :-
    \+ writable(E), !,
    Message = "an error whose term is nested too deeply to show (more than 5,000 levels)".
error_message_(ga_limit(Limit), Message) :- !,
    ga_guard:limit_message(Limit, Message).
error_message_(ga_refused(Why), Message) :- !,
    format(string(Message), "refused: ~w", [Why]).
error_message_(E, Message) :-
    E \= error(_, _),
    !,
    strip_agent_modules(E, E1),
    format(string(Message), "Unhandled exception: ~q", [E1]).
error_message_(E0, Message) :-
    strip_agent_modules(E0, E1),
    drop_useless_context(E1, E),
    catch(( '$messages':translate_message(E, Lines, []),
            lines_string(Lines, Message0)
          ), _, fail),
    Message0 \== "",
    !,
    Message = Message0.
error_message_(E, Message) :-
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
