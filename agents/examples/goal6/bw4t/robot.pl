% A BW4T robot's knowledge. What the other robots told us is kept as beliefs:
% claimed_index/1, claimed_block/1, gone/1, explored/1; missing/1 marks blocks not found
% where they were said to be.
:- dynamic claimed_index/1, claimed_block/1, gone/1, explored/1, missing/1.

% A room is a place with one neighbour; the drop zone is not searched.
room(R) :- zone(_, R, _, _, [_]), R \= 'DropZone'.
front_of_drop_zone(F) :- zone(_, 'DropZone', _, _, [F]).
needed(I, Colour) :- sequence(Colours), nth0(I, Colours, Colour).
done :- sequence(Colours), length(Colours, N), sequenceIndex(N).

free_index(I) :- sequenceIndex(S), sequence(Colours), length(Colours, N), Last is N - 1,
    between(S, Last, I), \+ claimed_index(I), !.
known_block(B, Colour, R) :- block(B, Colour, R), \+ gone(B), \+ missing(B).
unexplored(R) :- room(R), \+ visited(R), \+ explored(R).
holding_any :- holding(_).
