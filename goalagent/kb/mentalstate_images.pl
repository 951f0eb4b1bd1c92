
		 /*******************************
		 *     IMAGES OF A LAUNCH       *
		 *******************************/

%   What loading a program's knowledge and beliefs, or declaring its update formulas, did
%   to the first agent's two modules, kept and done again to the next agents' own without
%   reading, confining or converting the texts (issue 29: launching 10,000 copies of an
%   agent reads its program once). load_term/6, ensure_dynamic/2 and make_own/2 in
%   mentalstate_load.pl tell note_loaded/1 what they do while an image is recorded.

:- dynamic(('$ga_image'/4, '$ga_loaded'/1)).

%!  load_imaged(+Id, +B, +G, +Items, +Sandbox, +RunsCode, -Result) is det.
%   As load/6 for a program without directives whose items, sandbox and RunsCode are those
%   of every load under the image number Id: the first such load records what it did to
%   the two modules once the texts were read and confined (the image, '$ga_image'/4: each
%   clause added, predicate declared dynamic and system predicate redefined, in order),
%   the next do the same to theirs without reading or confining the texts again
%   (launching 10,000 copies of an agent reads its knowledge and beliefs once). A program
%   whose clauses name anything else of the first agent's (confine_keys.pl) or that does
%   not load makes no image. Result: as load/6's, or imaged when the program is loaded
%   and its image kept (the next loads need not be handed the Items).

load_imaged(Id, B, G, _, Sandbox, _, imaged) :-
    '$ga_image'(Id, _, _, _),
    !,
    (   Sandbox == true -> ga_confine:load_sandbox ; true ),
    assertz(B:'$ga_confine'(Sandbox)),
    replay_image(Id, B, G).
load_imaged(Id, B, G, Items, Sandbox, RunsCode, Result) :-
    imaged(Id, B, G, load(B, G, Items, Sandbox, RunsCode, Result0), Result0, Result).

%!  declare_imaged(+Id, +B, +G, +Formulas, -Result) is det.
%   As declare/4, for agents whose modules hold the same (loaded from one image, Id
%   numbering the image and the formulas): the first records what it did, the next do
%   the same without reading the formulas.

declare_imaged(Id, B, G, _, imaged) :-
    '$ga_image'(Id, _, _, _),
    !,
    replay_image(Id, B, G).
declare_imaged(Id, B, G, Formulas, Result) :-
    imaged(Id, B, G, declare(B, G, Formulas, Result0), Result0, Result).

%   imaged(+Id, +B, +G, :Goal, ?Result0, -Result): runs Goal, which sets Result0, and
%   keeps what it did to the modules B and G as image Id when Result0 is ok and nothing
%   of it names anything else of that agent's: Result is then imaged (the next calls are
%   handed no texts), else Result0.
imaged(Id, B, G, Goal, Result0, Result) :-
    imaged_(Id, B, G, Goal, Result0),
    (   Result0 == ok, '$ga_image'(Id, _, _, _)
    ->  Result = imaged
    ;   Result = Result0
    ).

imaged_(Id, B, G, Goal, Result) :-
    retractall('$ga_loaded'(_)),
    nb_setval('$ga_recording', true),
    call_cleanup(Goal, nb_setval('$ga_recording', false)),
    findall(Effect, retract('$ga_loaded'(Effect)), Effects0),
    maplist(module_role(B, G), Effects0, Effects),
    sub_atom(B, 5, _, 0, Secret),                   % ga_b_<secret>, ga_g_<secret>
    (   Result == ok,
        forall(member(Effect, Effects), ( arg(1, Effect, Role), memberchk(Role, [b, g]) )),
        \+ ( sub_term(Text, Effects), ( atom(Text) ; string(Text) ),
             Text \== B, Text \== G, sub_atom(Text, _, _, _, Secret) )
    ->  (   sub_term(Text, Effects), ( Text == B ; Text == G )
        ->  assertz('$ga_image'(Id, B, G, Effects))
        ;   assertz('$ga_image'(Id, none, none, Effects))
        )
    ;   true
    ).

%   replay_image(+Id, +B, +G): does to B and G what image Id records (their module names
%   in its clauses renamed). A predicate declared dynamic again stays as it is, and one
%   already the agent's own is not redefined (as ensure_dynamic/2 and make_own/2 leave
%   them), so declaring from an image is declaring whenever it is done.
replay_image(Id, B, G) :-
    '$ga_image'(Id, FromB, FromG, Effects0),
    (   FromB == none
    ->  Effects = Effects0
    ;   renamed(Effects0, [FromB-B, FromG-G], Effects)
    ),
    ga_sizes:with_optimise(ga_kb:forall(member(Effect, Effects), replay(Effect, B, G))).

%   note_loaded(+Effect): Effect (what load/6 did to a module) recorded for load_imaged/7
%   while it records.
note_loaded(Effect) :-
    (   nb_current('$ga_recording', true)
    ->  assertz('$ga_loaded'(Effect))
    ;   true
    ).

%   module_role(+B, +G, +Effect0, -Effect): the effect's module named by its role, b or g
%   (any other module, named as it is, keeps the effects from making an image).
module_role(B, G, Effect0, Effect) :-
    Effect0 =.. [Kind, M0, What],
    (   M0 == B -> M = b ; M0 == G -> M = g ; M = M0 ),
    Effect =.. [Kind, M, What].

replay(Effect, B, G) :-
    Effect =.. [Kind, Role, What],
    (   Role == b -> M = B ; M = G ),
    replay_(Kind, M, What).

replay_(assert, M, Clause) :- assertz(M:Clause).     % (optimised, as loaded_assertz/2)
replay_(dynamic, M, PI) :- dynamic(M:PI).
replay_(redefine, M, Head) :-                   % as make_own/2: not once it is M's own
    (   predicate_property(M:Head, implementation_module(system))
    ->  redefine_system_predicate(M:Head)
    ;   true
    ).
