claims(0).  % how many calls this car has claimed: numbers its claim messages
