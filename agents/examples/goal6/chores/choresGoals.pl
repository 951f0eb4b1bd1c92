done(dishes).
done(laundry).
done(ironing).
