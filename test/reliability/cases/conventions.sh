# Angles from the hanging position (--theta1, --theta2; q = theta - pi/2), accepted
# wherever --q1, --q2 are (one set of conventions).
succeed cnv-sim-theta              -- simulate --theta1 0.3 --theta2 -0.2 --t-end 0.01 --output th.h5
succeed cnv-lya-theta              -- lyapunov --theta1 0.3 --t-end 0.1 --output th.h5
succeed cnv-div-theta              -- divergence --theta2 1 --t-end 0.5 --pairs 2 --lyapunov-t 0 --output th.h5
succeed cnv-swp-theta              -- sweep --theta1 0.2 --axis1 theta2 --axis2 w2 --n 4 --t-end 1 --quiet --output th.h5
succeed cnv-sim-theta-eq           -- simulate --theta1=0.5 --t-end 0.01 --output th.h5
refuse  cnv-sim-theta-nan  theta1  -- simulate --theta1 nan --output th.h5
refuse  cnv-sim-theta-inf  theta2  -- simulate --theta2 inf --output th.h5
refuse  cnv-sim-theta-big  theta2  -- simulate --theta2 1e7 --output th.h5
refuse  cnv-sim-theta-junk theta1  -- simulate --theta1 abc --output th.h5
refuse  cnv-sim-theta-none theta1  -- simulate --output th.h5 --theta1
refuse  cnv-lya-theta-big  theta1  -- lyapunov --theta1 -2e6 --output th.h5
refuse  cnv-poi-theta-nan  theta1  -- poincare --theta1 nan --output th.h5
refuse  cnv-stu-theta-big  theta1  -- study --quick --theta1 1e300 --output th.h5
