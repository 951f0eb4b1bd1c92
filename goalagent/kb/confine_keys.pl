/*  Each agent's own global variables, flags, recorded keys and gensym/2 counters
    (included into ga_confine). SWI-Prolog has one table of each for the whole process:
    without this, one agent's nb_setval(k, V) was every agent's nb_getval(k, V), and one
    agent's gensym(k, X) or reset_gensym/0 changed the names every other agent made, a
    channel between agents.
*/

%   agent_key(+G0, +Ctx, -G): global variables, flags and recorded keys are the process's;
%   each agent has its own. The key an agent names (never one of the runtime's, '$...',
%   ga_..., never enumerated) becomes its own: an atom that starts with its module's name
%   (ga_b_<secret>:Key), which no agent can write. A compound key stands for its name and
%   arity, as in SWI-Prolog's recorded database. The keys are noted in the agent's module
%   ('$ga_key'/2) and forgotten with it (forget_keys/1).
agent_key(G0, c(M, _, _), G) :-
    (   key_arg(G0, Key, Family)
    ->  (   var(Key)
        ->  refuse("~q with a key only known at run time", [G0])
        ;   atom(Key), ( sub_atom(Key, 0, _, _, $) ; sub_atom(Key, 0, _, _, ga_) )
        ->  refuse("the key ~q is reserved for the runtime", [Key])
        ;   own_key(Family, M, Key, Own)
        ->  G0 =.. [Name, _|Args],
            G =.. [Name, Own|Args],
            note_key(M, Family, Own)
        ;   G = G0                          % not a key: SWI-Prolog raises the type error
        )
    ;   G = G0
    ).

key_arg(G, Key, Family) :-
    functor(G, Name, Arity),
    key_family(Name/Arity, Family),
    arg(1, G, Key).

key_family(nb_setval/2, global).
key_family(b_setval/2, global).
key_family(nb_getval/2, global).
key_family(b_getval/2, global).
key_family(nb_current/2, global).
key_family(nb_delete/1, global).
key_family(nb_linkval/2, global).
key_family(flag/3, flag).
key_family(get_flag/2, flag).
key_family(set_flag/2, flag).
key_family(recorda/2, recorded).
key_family(recorda/3, recorded).
key_family(recordz/2, recorded).
key_family(recordz/3, recorded).
key_family(recorded/2, recorded).
key_family(recorded/3, recorded).

own_key(global, M, Key, Own) :-
    atom(Key),
    format(atom(Own), '~w:~w', [M, Key]).
own_key(Family, M, Key, Own) :-
    Family \== global,
    (   atom(Key) -> format(atom(Own), '~w:~w', [M, Key])
    ;   integer(Key) -> format(atom(Own), '~w#~d', [M, Key])
    ;   compound(Key) -> compound_name_arity(Key, Name, Arity),
        format(atom(Own), '~w/~w/~d', [M, Name, Arity])
    ).

note_key(M, Family, Key) :-
    (   M:'$ga_key'(Family, Key)
    ->  true
    ;   assertz(M:'$ga_key'(Family, Key))
    ).

%   agent_counter(+G, +Ctx, -Prepared): library(gensym) keeps its counters in the process's
%   flags ('$gs_'Base); an agent's gensym/2 and reset_gensym/0,1 count in flags of its own
%   (noted as its keys are).
agent_counter(gensym(Base, Atom), c(M, _, _), ga_confine:agent_gensym(M, Base, Atom)).
agent_counter(reset_gensym(Base), c(M, _, _), ga_confine:agent_reset_gensym(M, Base)).
agent_counter(reset_gensym, c(M, _, _), ga_confine:agent_reset_gensym(M)).

agent_gensym(M, Base, Atom) :-
    gensym_key(M, Base, Key),
    flag(Key, Old, Old + 1),
    note_key(M, flag, Key),
    New is Old + 1,
    atom_concat(Base, New, Atom).

agent_reset_gensym(M, Base) :-
    gensym_key(M, Base, Key),
    (   M:'$ga_key'(flag, Key) -> flag(Key, _, 0) ; true ).

agent_reset_gensym(M) :-
    format(atom(Prefix), '~w:$gs_', [M]),
    forall(( M:'$ga_key'(flag, Key), sub_atom(Key, 0, _, _, Prefix) ), flag(Key, _, 0)).

gensym_key(M, Base, Key) :-
    must_be(atomic, Base),
    format(atom(Key), '~w:$gs_~w', [M, Base]).

%!  forget_keys(+M) is det.
%   Frees the global variables and recorded keys of the agent of module M (its flags are
%   only set to 0: SWI-Prolog cannot delete a flag).
forget_keys(M) :-
    forall(M:'$ga_key'(Family, Key), forget_key(Family, Key)).

forget_key(global, Key) :-
    (   nb_current(Key, _) -> nb_delete(Key) ; true ).
forget_key(flag, Key) :-
    flag(Key, _, 0).
forget_key(recorded, Key) :-
    forall(recorded(Key, _, Ref), erase(Ref)).
