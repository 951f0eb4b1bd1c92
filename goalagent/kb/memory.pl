/*  How much memory an agent takes (goalagent/kb/memory.py, --max-memory): what its
    clauses hold, and what one of its calls takes outside Prolog's stacks. Loaded once per
    process beside mentalstate.pl; Python and the watchdog's signals call the predicates
    documented with %!.

    SWI-Prolog 9 bounds each thread's stacks (stack_limit, 1 GB: terms, strings, big
    integers while a query runs) but nothing else: atoms, clauses, text being written to a
    string or atom, are malloc()ed without limit, and one process holds every agent. So
    the runtime measures them itself, never on the cycle's path: the watchdog thread reads
    the process's resident memory every tick (watchdog.py) and, when it has grown, asks
    for an account -- in the running call (stretch_signal/2 in guard.pl) and at each
    agent's next interpreter call. An agent over its budget is stopped; the process, and
    the other agents, live on.

    An agent's held bytes: SWI's own size of every predicate of its two modules (clauses,
    their code and indexes: knowledge, beliefs, goals, percepts, mailbox, compiled
    conditions), the terms it keeps under its own global variables and recorded keys
    (confine_keys.pl: nb_setval/2, recordz/2; a 2 MB list kept under a new key each cycle
    grew the process without end), and the text of the atoms those clauses hold (an atom
    costs its text once in the process, but an agent that keeps a 50 MB atom in each of
    its facts is charged for each). The atoms are only walked when the process's atoms
    could push it over.
*/
:- module(ga_memory, []).

:- set_prolog_flag(generate_debug_info, false).

%   '$ga_mem_gen': Generation-AtomSpace, the atom space measured (after an atom garbage
%   collection) for the watchdog's last alarm.
:- initialization(nb_setval('$ga_mem_gen', -1-0)).

%!  account(+B, +Max, +Generation, -Result) is det.
%   The agent whose belief module is B, allowed Max bytes, after the watchdog's alarm
%   number Generation (the first account of a generation collects the process's garbage
%   atoms first: SWI collects them by count, and a few huge atoms never trigger it).
%   Result = ok, or over(Bytes): it holds Bytes > Max.
account(B, Max, Generation, Result) :-
    atom_space(Generation, AtomSpace),
    held(B, Max, AtomSpace, Bytes),
    (   Bytes > Max
    ->  Result = over(Bytes)
    ;   Result = ok
    ).

atom_space(Generation, AtomSpace) :-
    nb_getval('$ga_mem_gen', Seen-AtomSpace0),
    (   Seen =:= Generation
    ->  AtomSpace = AtomSpace0
    ;   garbage_collect_atoms,
        trim_heap,                          % give what was freed back to the system
        statistics(atom_space, AtomSpace),
        nb_setval('$ga_mem_gen', Generation-AtomSpace)
    ).

%   held(+B, +Max, +AtomSpace, -Bytes): what the agent holds (see the header); its atoms'
%   text is only added when all the process's atoms together could put it over Max.
held(B, Max, AtomSpace, Bytes) :-
    B:'$ga_gm'(G),
    module_bytes(B, InB),
    module_bytes(G, InG),
    keys_bytes(B, InKeys),
    Clauses is InB + InG + InKeys,
    (   Clauses + AtomSpace =< Max
    ->  Bytes = Clauses
    ;   Clauses > Max
    ->  Bytes = Clauses
    ;   module_atom_text(B, TextB),
        module_atom_text(G, TextG),
        Bytes is Clauses + TextB + TextG
    ).

module_bytes(M, Bytes) :-
    aggregate_all(sum(S),
                  ( own_predicate(M, Head),
                    predicate_property(M:Head, size(S)) ),
                  Bytes).

%   keys_bytes(+B, -Bytes): the terms under the agent's own global variables and recorded
%   keys, each at what it takes: a global variable is a copy on the global stack, a word
%   (8 bytes) per cell (term_size/2); a record is compiled to a compact code, about the size
%   of its serialized form (a 300,000-integer list: 1.7 MB, not its 7 MB of cells). Charging
%   records by their cells let an agent be charged three times what the process grew by, so
%   the watchdog's alarm, which follows the process's growth, came when the agent was
%   charged anywhere from 3 to 5 budgets.
keys_bytes(B, Bytes) :-
    aggregate_all(sum(KeyBytes), ( catch(B:'$ga_key'(Family, Key), _, fail),
                                   key_bytes(Family, Key, KeyBytes) ), Bytes).

key_bytes(global, Key, Bytes) :-
    nb_current(Key, Value),
    term_size(Value, Cells),
    Bytes is Cells * 8.
key_bytes(recorded, Key, Bytes) :-
    recorded(Key, Value),
    fast_term_serialized(Value, Serialized),
    string_length(Serialized, Bytes).

own_predicate(M, Head) :-
    current_predicate(_, M:Head),
    \+ predicate_property(M:Head, imported_from(_)),
    \+ predicate_property(M:Head, foreign).

module_atom_text(M, Bytes) :-
    aggregate_all(sum(N),
                  ( own_predicate(M, Head),
                    \+ predicate_property(M:Head, number_of_clauses(0)),
                    clause(M:Head, Body),
                    term_text(Head-Body, 0, N) ),
                  Bytes).

%   term_text(@Term, +N0, -N): N0 plus the characters of the atoms in Term, each
%   occurrence (the last argument in tail position: long lists need no stack).
term_text(T, N0, N) :-
    (   atom(T)
    ->  atom_length(T, L),
        N is N0 + L
    ;   compound(T)
    ->  compound_name_arity(T, _, Arity),
        term_text_args(1, Arity, T, N0, N)
    ;   N = N0
    ).

term_text_args(I, Arity, T, N0, N) :-
    arg(I, T, Arg),
    (   I =:= Arity
    ->  term_text(Arg, N0, N)
    ;   term_text(Arg, N0, N1),
        I1 is I + 1,
        term_text_args(I1, Arity, T, N1, N)
    ).

%!  call_growth(+B, +Max, +Base, +Page) is det.
%   Sent by the watchdog into a running call of the agent of belief module B (allowed Max
%   bytes) when the process's resident memory has grown past Max since the call began (it
%   was Base pages of Page bytes then, or at the watchdog's look before: earlier calls'
%   growth may be in it). First what the agent holds is checked (the garbage atoms
%   collected); then what the process has grown by that is neither Prolog's stacks
%   (bounded by SWI's stack_limit, and given back when the query ends) nor held in its
%   clauses is what the call took -- text written to an atom or string, atoms it still
%   reaches -- and over Max the agent is stopped. Nothing for a closed agent (live_agent/1).
call_growth(B, Max, Base, Page) :-
    live_agent(B), !,
    held_bytes(B, Max, Held),
    setup_call_cleanup(open('/proc/self/statm', read, In),
                       read_line_to_string(In, Line),
                       close(In)),
    split_string(Line, " ", "", [_, Resident|_]),
    number_string(Pages, Resident),
    statistics(stack, Stacks),
    Outside is (Pages - Base) * Page - Stacks - Held,
    (   Outside > Max
    ->  throw(ga_limit(memory(call(Outside), Max)))
    ;   true
    ).
call_growth(_, _, _, _).

%!  held_check(+B, +Max) is det.
%   Sent by the watchdog into a running call of the agent of belief module B when the
%   process's memory has grown past its alarm: throws ga_limit(memory(held(Bytes), Max))
%   when the agent holds more than Max bytes. Nothing for a closed agent (live_agent/1).
held_check(B, Max) :-
    (   live_agent(B)
    ->  held_bytes(B, Max, _)
    ;   true
    ).

%   live_agent(+B): B is the belief module of an agent not closed. The watchdog's note of
%   the running agent outlives its calls: a query of no agent's (reading a text, checking
%   a file) may run when its signal comes, after that agent was closed (its '$ga_gm'/1
%   then unknown: the query failed with that error, once in a suite run).
live_agent(B) :-
    current_predicate(B:'$ga_gm'/1).

held_bytes(B, Max, Bytes) :-
    garbage_collect_atoms,
    trim_heap,
    statistics(atom_space, AtomSpace),
    held(B, Max, AtomSpace, Bytes),
    (   Bytes > Max
    ->  throw(ga_limit(memory(held(Bytes), Max)))
    ;   true
    ).
