set title 'P1 sine-Gordon on [0, 1]: CPU time to reach error 1e-06' noenhanced
set xlabel 'N (grid points)'
set ylabel 'CPU time (s)'
set logscale xy
set format xy '10^{%L}'
set grid lc rgb '#dddddd'
set key outside right top noenhanced spacing 1.15
set logscale x 2
set format x '%g'
set terminal pngcairo size 1000,620 enhanced font 'DejaVu Sans,11'
set output 'scaling.png'
plot 'data/scaling_serkn2s4.dat' u 1:2 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'SERKN2s4', \
  'data/scaling_saba3.dat' u 1:2 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA3', \
  'data/scaling_serkn3s4pf_1.dat' u 1:2 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SERKN3s4pf(1)', \
  'data/scaling_st_rmer_verlet.dat' u 1:2 w lp lc rgb '#9467bd' dt (2,4) lw 2.2 pt 4 ps 1.0 t 'Störmer–Verlet', \
  'data/scaling_odeint_sb3a_mclachlan.dat' u 1:2 w lp lc rgb '#ff7f0e' dt (2,4) lw 2.2 pt 6 ps 1.0 t 'Odeint sb3a (McLachlan)', \
  'data/scaling_odeint_sb3a_m4_mclachlan.dat' u 1:2 w lp lc rgb '#8c564b' dt (2,4) lw 2.2 pt 8 ps 1.0 t 'Odeint sb3a-m4 (McLachlan)', \
  'data/scaling_gauss2_order_4.dat' u 1:2 w lp lc rgb '#e377c2' dt (2,4) lw 2.2 pt 10 ps 1.0 t 'Gauss2 (order 4)', \
  'data/scaling_strang_impulse.dat' u 1:2 w lp lc rgb '#17becf' dt (2,4) lw 2.2 pt 12 ps 1.0 t 'Strang (impulse)', \
  'data/scaling_blanes_moan_srkn6b.dat' u 1:2 w lp lc rgb '#7f7f7f' dt (2,4) lw 2.2 pt 14 ps 1.0 t 'Blanes–Moan SRKN6b', \
  'data/scaling_blanes_moan_srkn14a.dat' u 1:2 w lp lc rgb '#bcbd22' dt (2,4) lw 2.2 pt 16 ps 1.0 t 'Blanes–Moan SRKN14a', \
  'data/scaling_aba_10_6_4.dat' u 1:2 w lp lc rgb '#393b79' dt (2,4) lw 2.2 pt 18 ps 1.0 t 'ABA(10,6,4)', \
  'data/scaling_mollified_impulse_sinc.dat' u 1:2 w lp lc rgb '#637939' dt (2,4) lw 2.2 pt 20 ps 1.0 t 'mollified impulse (sinc)', \
  'data/scaling_omf4_4mn3f3gp.dat' u 1:2 w lp lc rgb '#8c6d31' dt (2,4) lw 2.2 pt 22 ps 1.0 t 'OMF4 (4MN3F3GP)', \
  'data/scaling_pmlf6_processed.dat' u 1:2 w lp lc rgb '#843c39' dt (2,4) lw 2.2 pt 24 ps 1.0 t 'PMLF6 (processed)'
set terminal svg size 1000,620 dynamic enhanced font 'DejaVu Sans,11'
set output 'scaling.svg'
plot 'data/scaling_serkn2s4.dat' u 1:2 w lp lc rgb '#1f77b4' dt 1 lw 2.2 pt 7 ps 0.9 t 'SERKN2s4', \
  'data/scaling_saba3.dat' u 1:2 w lp lc rgb '#d62728' dt 1 lw 2.2 pt 7 ps 0.9 t 'SABA3', \
  'data/scaling_serkn3s4pf_1.dat' u 1:2 w lp lc rgb '#2ca02c' dt 1 lw 2.2 pt 7 ps 0.9 t 'SERKN3s4pf(1)', \
  'data/scaling_st_rmer_verlet.dat' u 1:2 w lp lc rgb '#9467bd' dt (2,4) lw 2.2 pt 4 ps 1.0 t 'Störmer–Verlet', \
  'data/scaling_odeint_sb3a_mclachlan.dat' u 1:2 w lp lc rgb '#ff7f0e' dt (2,4) lw 2.2 pt 6 ps 1.0 t 'Odeint sb3a (McLachlan)', \
  'data/scaling_odeint_sb3a_m4_mclachlan.dat' u 1:2 w lp lc rgb '#8c564b' dt (2,4) lw 2.2 pt 8 ps 1.0 t 'Odeint sb3a-m4 (McLachlan)', \
  'data/scaling_gauss2_order_4.dat' u 1:2 w lp lc rgb '#e377c2' dt (2,4) lw 2.2 pt 10 ps 1.0 t 'Gauss2 (order 4)', \
  'data/scaling_strang_impulse.dat' u 1:2 w lp lc rgb '#17becf' dt (2,4) lw 2.2 pt 12 ps 1.0 t 'Strang (impulse)', \
  'data/scaling_blanes_moan_srkn6b.dat' u 1:2 w lp lc rgb '#7f7f7f' dt (2,4) lw 2.2 pt 14 ps 1.0 t 'Blanes–Moan SRKN6b', \
  'data/scaling_blanes_moan_srkn14a.dat' u 1:2 w lp lc rgb '#bcbd22' dt (2,4) lw 2.2 pt 16 ps 1.0 t 'Blanes–Moan SRKN14a', \
  'data/scaling_aba_10_6_4.dat' u 1:2 w lp lc rgb '#393b79' dt (2,4) lw 2.2 pt 18 ps 1.0 t 'ABA(10,6,4)', \
  'data/scaling_mollified_impulse_sinc.dat' u 1:2 w lp lc rgb '#637939' dt (2,4) lw 2.2 pt 20 ps 1.0 t 'mollified impulse (sinc)', \
  'data/scaling_omf4_4mn3f3gp.dat' u 1:2 w lp lc rgb '#8c6d31' dt (2,4) lw 2.2 pt 22 ps 1.0 t 'OMF4 (4MN3F3GP)', \
  'data/scaling_pmlf6_processed.dat' u 1:2 w lp lc rgb '#843c39' dt (2,4) lw 2.2 pt 24 ps 1.0 t 'PMLF6 (processed)'
unset output
