set logscale xy
set grid lc rgb '#dddddd'
set key outside right top noenhanced
set title '2-D sine-Gordon, periodic: CPU time to error 1e-06' noenhanced
set xlabel 'N (points per axis)'
set ylabel 'CPU time (s)'
set logscale x 2
set terminal pngcairo size 1000,620 font 'DejaVu Sans,11'
set output 'grid_sg2d_cpu.png'
plot 'data/grid_sg2d_serkn2s4.dat' u 1:2 w lp lw 2 dt 1 pt 7 t 'SERKN2s4', \
  'data/grid_sg2d_sdt7x_4.dat' u 1:2 w lp lw 2 dt 1 pt 7 t 'SDT7x(4)', \
  'data/grid_sg2d_st_rmer_verlet.dat' u 1:2 w lp lw 2 dt (2,4) pt 4 t 'Störmer–Verlet', \
  'data/grid_sg2d_strang_impulse.dat' u 1:2 w lp lw 2 dt (2,4) pt 4 t 'Strang (impulse)', \
  'data/grid_sg2d_blanes_moan_srkn6b.dat' u 1:2 w lp lw 2 dt (2,4) pt 4 t 'Blanes–Moan SRKN6b', \
  'data/grid_sg2d_blanes_moan_srkn14a.dat' u 1:2 w lp lw 2 dt (2,4) pt 4 t 'Blanes–Moan SRKN14a', \
  'data/grid_sg2d_omf4_4mn3f3gp.dat' u 1:2 w lp lw 2 dt (2,4) pt 4 t 'OMF4 (4MN3F3GP)', \
  'data/grid_sg2d_pmlf6_processed.dat' u 1:2 w lp lw 2 dt (2,4) pt 4 t 'PMLF6 (processed)'
set terminal svg size 1000,620 dynamic font 'DejaVu Sans,11'
set output 'grid_sg2d_cpu.svg'
plot 'data/grid_sg2d_serkn2s4.dat' u 1:2 w lp lw 2 dt 1 pt 7 t 'SERKN2s4', \
  'data/grid_sg2d_sdt7x_4.dat' u 1:2 w lp lw 2 dt 1 pt 7 t 'SDT7x(4)', \
  'data/grid_sg2d_st_rmer_verlet.dat' u 1:2 w lp lw 2 dt (2,4) pt 4 t 'Störmer–Verlet', \
  'data/grid_sg2d_strang_impulse.dat' u 1:2 w lp lw 2 dt (2,4) pt 4 t 'Strang (impulse)', \
  'data/grid_sg2d_blanes_moan_srkn6b.dat' u 1:2 w lp lw 2 dt (2,4) pt 4 t 'Blanes–Moan SRKN6b', \
  'data/grid_sg2d_blanes_moan_srkn14a.dat' u 1:2 w lp lw 2 dt (2,4) pt 4 t 'Blanes–Moan SRKN14a', \
  'data/grid_sg2d_omf4_4mn3f3gp.dat' u 1:2 w lp lw 2 dt (2,4) pt 4 t 'OMF4 (4MN3F3GP)', \
  'data/grid_sg2d_pmlf6_processed.dat' u 1:2 w lp lw 2 dt (2,4) pt 4 t 'PMLF6 (processed)'
unset output
set title '2-D sine-Gordon, periodic: time per step against d' noenhanced
set xlabel 'd (unknowns)'
set ylabel 'seconds per step'
set logscale x 10
set terminal pngcairo size 1000,620 font 'DejaVu Sans,11'
set output 'grid_sg2d_step.png'
plot 'data/grid_sg2d_step_sdt7x_4.dat' u 1:2 w p pt 7 ps 1.3 t 'SDT7x(4)', 'data/grid_sg2d_step_sdt7x_4.dat' u 1:3 w l lw 1.5 t 'SDT7x(4): fit c d log2 d', \
  'data/grid_sg2d_step_serkn2s4.dat' u 1:2 w p pt 7 ps 1.3 t 'SERKN2s4', 'data/grid_sg2d_step_serkn2s4.dat' u 1:3 w l lw 1.5 t 'SERKN2s4: fit c d log2 d', \
  'data/grid_sg2d_step_omf4_4mn3f3gp.dat' u 1:2 w p pt 7 ps 1.3 t 'OMF4 (4MN3F3GP)', 'data/grid_sg2d_step_omf4_4mn3f3gp.dat' u 1:3 w l lw 1.5 t 'OMF4 (4MN3F3GP): fit c d log2 d'
set terminal svg size 1000,620 dynamic font 'DejaVu Sans,11'
set output 'grid_sg2d_step.svg'
plot 'data/grid_sg2d_step_sdt7x_4.dat' u 1:2 w p pt 7 ps 1.3 t 'SDT7x(4)', 'data/grid_sg2d_step_sdt7x_4.dat' u 1:3 w l lw 1.5 t 'SDT7x(4): fit c d log2 d', \
  'data/grid_sg2d_step_serkn2s4.dat' u 1:2 w p pt 7 ps 1.3 t 'SERKN2s4', 'data/grid_sg2d_step_serkn2s4.dat' u 1:3 w l lw 1.5 t 'SERKN2s4: fit c d log2 d', \
  'data/grid_sg2d_step_omf4_4mn3f3gp.dat' u 1:2 w p pt 7 ps 1.3 t 'OMF4 (4MN3F3GP)', 'data/grid_sg2d_step_omf4_4mn3f3gp.dat' u 1:3 w l lw 1.5 t 'OMF4 (4MN3F3GP): fit c d log2 d'
unset output
